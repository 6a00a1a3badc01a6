//! # hagfish-stats
//!
//! The uncertainty of a parameter study whose runs are chaotic: a knot's speed or a slide
//! force changes from run to run under perturbations far below the model's accuracy, so each
//! grid point is run N = 3…30 times and reported as an estimate with an interval, not as one
//! number.
//!
//! - [`mean_interval`]: a studentized bootstrap (bootstrap-t) confidence interval of the mean
//!   of a grid point's replicates — for a continuous outcome (speed in cm/s, force in dyn).
//!   Chosen over the percentile bootstrap because at N = 8 the percentile interval covers a
//!   normal mean only ≈ 89 % of the time at nominal 95 %; the measured coverages are in the
//!   module [`bootstrap`].
//! - [`wilson_interval`]: the Wilson score interval of a success rate — for a yes/no outcome
//!   (did the knot tie, did it reach the head) over the replicates.
//! - [`Summary`]: n, mean and sample sd (n − 1 divisor) of the replicates.
//! - [`normal_quantile`] and [`quantile_sorted`]: the two quantile rules the intervals use.
//!
//! Every result is deterministic: the bootstrap draws from a ChaCha8 stream fixed by its
//! seed, and it sorts the replicates first, so the order in which a sweep's runs finished
//! does not change an interval. Empty, short, non-finite or degenerate input gives `None` or
//! the documented degenerate value; nothing here panics on user input.

pub mod bootstrap;
mod draw;
mod normal;
mod quantile;
mod summary;
mod wilson;

pub use bootstrap::{Interval, mean_interval};
pub use normal::normal_quantile;
pub use quantile::quantile_sorted;
pub use summary::Summary;
pub use wilson::wilson_interval;
