//! Starting points of the narrow-phase search.
//!
//! Newton converges to the minimum whose basin it starts in. Two strands lying side by
//! side give a flat distance with several shallow minima, often one with a parameter on a
//! segment end right next to an interior one of almost the same depth, so the search is
//! started from several points (and once more from a probe next to a bound), and the
//! closest result wins.

use crate::chord::closest_chord_parameters;
use crate::sampled_segment::{GRID_SAMPLES, SampledSegment};
use crate::segment::Segment;

/// Intervals per parameter of the grid that seeds the searches ((n + 1)² samples of f).
pub(crate) const SEED_GRID_INTERVALS: usize = 8;

/// At most this many grid minima start a search (besides the chord start). Two strands
/// lying side by side give a flat distance with several shallow minima, and only searching
/// each basin finds the deepest.
///
/// Measured with this 9 × 9 grid, 4 starts and the edge probes on 4·10⁵ random pairs of
/// body-like segments (steps 0.424 ± 20 % cm, bends ≤ 75°) and 4·10⁵ pairs with arbitrary
/// control points in a 1 cm cube: no body-like search and one arbitrary one (by 1.2e-6 cm)
/// converged more than 1e-6 cm above the sampled global minimum. Without the probes, or
/// with one start, misses were 10⁻⁵–10⁻³.
const MAX_GRID_STARTS: usize = 4;

/// Samples per grid interval probed next to a bound after the searches (a dip narrower
/// than the grid right next to a segment end is the one case the grid misses).
const EDGE_PROBES: usize = 8;

/// Starting points of the searches: the chords' closest points, then the
/// [`MAX_GRID_STARTS`] deepest grid minima of f, deepest first.
///
/// A grid minimum is a point of the (n + 1)² grid that, along s_a and along s_b, either
/// lies on the edge of the box, or is not undercut by its two neighbours, or starts a grid
/// interval over which that gradient component changes sign from − to + (a dip narrower
/// than the grid). Edges are exempt so that the minima of f restricted to an edge count:
/// the closest points of two strands often have one parameter on a segment end, right
/// next to an interior minimum of almost the same depth.
pub(crate) struct Starts {
    chord: [f64; 2],
    /// Grid minima (s_a, s_b), deepest first, valid up to `found`.
    grid_minima: [[f64; 2]; MAX_GRID_STARTS],
    found: usize,
    /// f at the closest grid point (the deepest grid minimum).
    depth: f64,
}

impl Starts {
    /// The starting points for segments `a` and `b`, from their seed-grid samples.
    pub(crate) fn new(a: &SampledSegment, b: &SampledSegment) -> Starts {
        const N: usize = GRID_SAMPLES;
        let grid = |i: usize| i as f64 / SEED_GRID_INTERVALS as f64;
        // f = |Δ|² and the components of the gradient of ½f along s_a and s_b at every grid
        // point, Δ = x_b(s_j) − x_a(s_i), coordinate by coordinate (same operations and
        // order as the DVec3 dot products, so the same values).
        let mut f = [[0.0; N]; N];
        let mut g_a = [[0.0; N]; N];
        let mut g_b = [[0.0; N]; N];
        let ([bx, by, bz], [tbx, tby, tbz]) = (&b.points, &b.tangents);
        for i in 0..N {
            let (ax, ay, az) = (a.points[0][i], a.points[1][i], a.points[2][i]);
            let (tax, tay, taz) = (a.tangents[0][i], a.tangents[1][i], a.tangents[2][i]);
            for j in 0..N {
                let (dx, dy, dz) = (bx[j] - ax, by[j] - ay, bz[j] - az);
                f[i][j] = dx * dx + dy * dy + dz * dz;
                g_a[i][j] = -(tax * dx + tay * dy + taz * dz);
                g_b[i][j] = tbx[j] * dx + tby[j] * dy + tbz[j] * dz;
            }
        }
        // Whether each grid point is a grid minimum: true on the edges of the box along each
        // parameter, else not undercut by its two neighbours or the start of a − to + sign
        // change of that gradient component. Fixed ranges and non-short-circuit `&` and `|`
        // keep these loops free of branches.
        let mut minimum = [[true; N]; N];
        for i in 1..N - 1 {
            for j in 0..N {
                let here = f[i][j];
                minimum[i][j] = ((f[i - 1][j] >= here) & (f[i + 1][j] >= here))
                    | ((g_a[i][j] <= 0.0) & (g_a[i + 1][j] >= 0.0));
            }
        }
        for i in 0..N {
            for j in 1..N - 1 {
                let here = f[i][j];
                minimum[i][j] &= ((f[i][j - 1] >= here) & (f[i][j + 1] >= here))
                    | ((g_b[i][j] <= 0.0) & (g_b[i][j + 1] >= 0.0));
            }
        }
        // `depths[..found]` holds the f of `grid_minima[..found]`, ascending (ties in the
        // order of the grid).
        let mut depths = [f64::INFINITY; MAX_GRID_STARTS];
        let mut grid_minima = [[0.0; 2]; MAX_GRID_STARTS];
        let mut found = 0;
        for i in 0..N {
            for j in 0..N {
                let here = f[i][j];
                if !(minimum[i][j] & (here < depths[MAX_GRID_STARTS - 1])) {
                    continue;
                }
                let at = depths[..found].partition_point(|&d| d <= here);
                found = (found + 1).min(MAX_GRID_STARTS);
                depths.copy_within(at..found - 1, at + 1);
                grid_minima.copy_within(at..found - 1, at + 1);
                depths[at] = here;
                grid_minima[at] = [grid(i), grid(j)];
            }
        }
        let chord = closest_chord_parameters(a.segment.chord(), b.segment.chord());
        Starts { chord, grid_minima, found, depth: depths[0] }
    }

    /// The closest points of the two chords.
    pub(crate) fn chord(&self) -> [f64; 2] {
        self.chord
    }

    /// Lower bound on the distance of the segments over [0, 1]², from the closest grid
    /// point: every (s_a, s_b) is within half a grid interval of a grid point along each
    /// parameter, and the distance changes by at most the speed bound times the parameter
    /// change (`speeds` = [`Segment::speed_bound`] of a and b).
    pub(crate) fn distance_lower_bound(&self, speeds: [f64; 2]) -> f64 {
        let half_interval = 0.5 / SEED_GRID_INTERVALS as f64;
        self.depth.sqrt() - half_interval * (speeds[0] + speeds[1])
    }

    /// The deepest grid minima, deepest first.
    pub(crate) fn grid_minima(&self) -> &[[f64; 2]] {
        &self.grid_minima[..self.found]
    }
}

/// For a search result `found` (at squared distance `distance_squared`) with a parameter
/// on a bound, the closest of [`EDGE_PROBES`] points that sample the grid interval next to
/// that bound (the other parameter fixed), if it is closer than the result: a dip
/// narrower than the grid interval right next to a segment end, which the grid cannot see.
pub(crate) fn probe_next_to_bound(
    a: &Segment,
    b: &Segment,
    found: [f64; 2],
    distance_squared: f64,
) -> Option<[f64; 2]> {
    let mut best = (distance_squared, None);
    let interval = 1.0 / SEED_GRID_INTERVALS as f64;
    // (segment probed, its parameter, the other segment's fixed point, axis of the result)
    let axes = [(a, found[0], b.point(found[1]), 0), (b, found[1], a.point(found[0]), 1)];
    for (segment, s, fixed, axis) in axes {
        let inward = match s {
            0.0 => interval,
            1.0 => -interval,
            _ => continue,
        };
        for probe in 1..=EDGE_PROBES {
            let trial = s + inward * probe as f64 / EDGE_PROBES as f64;
            let f = segment.point(trial).distance_squared(fixed);
            if f < best.0 {
                let mut start = found;
                start[axis] = trial;
                best = (f, Some(start));
            }
        }
    }
    best.1
}
