//! Integration tests of `hagfish-anatomy`: one test binary, a module per subject.

mod errors;
mod es103;
mod mutations;
