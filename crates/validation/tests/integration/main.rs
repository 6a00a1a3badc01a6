//! Integration tests of `hagfish-validation`: one test binary.

mod frictional_knot;
mod overhand_pull;
mod rod_theory;
