//! Integration tests of `hagfish-scenario`: one test binary.

mod modal_space;
mod scenario_mutations;
