//! Acceptance tests of `hagfish-knots` (issue: knot analysis of an open centreline).

mod chirality;
mod closed_forms;
mod curves;
mod errors;
mod hagfish;
mod hagfish_curve;
mod invariance;
mod plat_path;
mod templates;
mod unknots;
