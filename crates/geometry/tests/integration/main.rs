//! Integration tests of `hagfish-geometry`: one test binary, a module per subject; `curves`
//! has the tangled centrelines the contact tests (and the broad-phase benchmark) use.

mod curves;

mod narrow_phase_vs_sampling;
mod no_missed_contacts;
