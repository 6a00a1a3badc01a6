//! Integration tests of `hagfish-scenario`: one test binary.

mod scenario_mutations;
