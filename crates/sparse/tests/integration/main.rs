//! Integration tests of `hagfish-sparse`: one test binary.

mod compressed_spans;
mod equivalence;
