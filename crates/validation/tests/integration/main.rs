//! Integration tests of `hagfish-validation`: one test binary.

mod frictional_knot;
mod rod_theory;
