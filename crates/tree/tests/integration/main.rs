//! Integration tests of `hagfish-tree`: one test binary, a module per subject; `common` has
//! the models and states they share.

mod common;

mod dynamics;
mod integrator;
mod jacobians;
mod kinematics;
