//! The claims of hagfish-stats measured: coverage of the true value by the intervals
//! (bootstrap-t by simulation, Wilson exactly) and the invariants that hold for any input.

mod bootstrap_coverage;
mod coverage;
mod invariants;
mod samples;
mod wilson_coverage;
