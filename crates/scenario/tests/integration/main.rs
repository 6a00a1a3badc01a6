//! Integration tests of `hagfish-scenario`: one test binary.

mod contact_margin;
mod modal_space;
mod polyline_shape;
mod scenario_mutations;
