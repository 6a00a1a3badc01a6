//! Integration tests of `hagfish-solver`: one test binary, a module per subject; `common` has
//! the random problems they share (and the contact-space benchmark includes).
//!
//! The binary's global allocator is `allocation-counter`'s, which counts per thread:
//! `allocations` asserts on its own thread's allocations while the other tests run.

mod common;

mod allocations;
mod compliant_rows;
mod friction;
mod own_row_kinds;
mod random_problems;
mod signs;
