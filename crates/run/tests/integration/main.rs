//! Integration tests of `hagfish-run`: one test binary, a module per subject; `common` is
//! the test controllers of `hagfish-sim`'s integration tests, included from there.
//!
//! The binary's global allocator is `allocation-counter`'s, which counts per thread:
//! `no_allocation` asserts on its own thread's allocations while the other tests run.

#[path = "../../../sim/tests/integration/common.rs"]
mod common;

mod checkpoint_corruption;
mod forming;
mod freshly_tied;
mod friction;
mod modal_space;
mod no_allocation;
mod recorded_loads;
mod recording_rate;
mod replay;
mod self_contact;
mod skin;
mod sparse_backend;
mod stop_request;
mod thigmotaxis;
