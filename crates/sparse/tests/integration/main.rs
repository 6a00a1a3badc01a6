//! Integration tests of `hagfish-sparse`: one test binary.

mod equivalence;
