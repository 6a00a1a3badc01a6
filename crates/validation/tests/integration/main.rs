//! Integration tests of `hagfish-validation`: one test binary.

mod rod_theory;
