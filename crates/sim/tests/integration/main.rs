//! Integration tests of `hagfish-sim`: one test binary, a module per subject; `common` has the
//! test controllers they share (and the sparse-backend tests of `hagfish-run` include).
//!
//! The binary's global allocator is `allocation-counter`'s, which counts per thread:
//! `linear_memory` asserts on its own thread's allocations while the other tests run.

mod common;

mod capstan;
mod constraints;
mod incline;
mod linear_memory;
mod moving_obstacle;
mod thin_obstacle;
