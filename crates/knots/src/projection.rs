//! Crossings of a closed polygon seen along a projection direction.
//!
//! The polygon is projected onto the plane orthogonal to the view direction v (f64); two
//! non-adjacent edges cross where their shadows intersect, and the edge with the larger
//! height v·x passes over. The diagram is only valid if the projection is *generic*: no
//! vertex on another edge's shadow, no two crossings at one point, distinct heights at each
//! crossing. Every such test is done with a margin ([`GENERICITY_TOLERANCE`] times the
//! curve's diameter, which [`crate::closure`] normalises to 1); a projection that fails any
//! of them is rejected as a whole and the caller tries another direction. Tests that pass
//! decide the diagram exactly as the exact projection would, because every quantity they
//! compare carries a rounding error far below the margin.

use glam::{DVec2, DVec3};

use crate::alexander::Crossing;

/// Margin of every genericity test, in units of the curve's diameter (the closure normalises
/// the curve to diameter 1; the far closure is at distance 100).
pub(crate) const GENERICITY_TOLERANCE: f64 = 1e-9;

/// The most crossings a diagram may have: the Alexander polynomial is a determinant of order
/// m − 1 over m crossings, O(m²) memory and O(m³) time per closure, so 500 crossings cost
/// ≈ 4 MB and a fraction of a second each. A hagfish knot shows tens; a curve that shows more
/// in a projection (a random walk of 100 000 points shows ≈ 10⁵) is refused
/// ([`crate::KnotError::TooManyCrossings`]) rather than exhausting the memory.
pub const MAX_CROSSINGS: usize = 500;

/// One edge of the projected polygon with its bounding box.
#[derive(Debug)]
struct Edge {
    start: DVec2,
    end: DVec2,
    start_height: f64,
    end_height: f64,
    min: DVec2,
    max: DVec2,
}

/// The bounding box of an edge in sweep order.
#[derive(Debug, Clone, Copy)]
struct SweepBox {
    min: DVec2,
    max: DVec2,
    edge: usize,
}

/// The buffers of [`Projector::crossings`], kept between calls so that voting over many
/// directions allocates once.
#[derive(Debug, Default)]
pub(crate) struct Projector {
    /// The vertices projected: position in the view plane and height along the view.
    points: Vec<(DVec2, f64)>,
    edges: Vec<Edge>,
    /// Sort keys: the leftmost x of an edge as a [`total_order_key`] in the high 64 bits,
    /// the edge's index in the low ones.
    keys: Vec<u128>,
    /// The edges' boxes sorted by leftmost x, then index.
    sweep: Vec<SweepBox>,
    /// Crossing positions along the curve, sorted for the genericity test.
    positions: Vec<f64>,
    /// Whether a projection since the last [`Projector::reset_limit`] had more than
    /// [`MAX_CROSSINGS`] crossings (and was given up).
    pub(crate) over_limit: bool,
}

impl Projector {
    /// Forgets that a projection had too many crossings.
    pub(crate) fn reset_limit(&mut self) {
        self.over_limit = false;
    }

    /// Writes into `found` the crossings of the closed polygon `vertices` (the last vertex
    /// joins the first) seen along the unit vector `view`, and returns whether this
    /// projection is generic (`found` means nothing if not). A projection with more than
    /// [`MAX_CROSSINGS`] crossings is given up (not generic) and marks `over_limit`.
    /// Crossing positions are `edge index + parameter along the edge`.
    pub(crate) fn crossings(
        &mut self,
        vertices: &[DVec3],
        view: DVec3,
        found: &mut Vec<Crossing>,
    ) -> bool {
        let (e1, e2) = view.any_orthonormal_pair();
        let n = vertices.len();
        self.points.clear();
        self.points
            .extend(vertices.iter().map(|&x| (DVec2::new(e1.dot(x), e2.dot(x)), view.dot(x))));
        let points = &self.points;
        self.edges.clear();
        let ends = points.iter().skip(1).chain(points.first());
        self.edges.extend(points.iter().zip(ends).map(
            |(&(start, start_height), &(end, end_height))| Edge {
                start,
                end,
                start_height,
                end_height,
                min: start.min(end),
                max: start.max(end),
            },
        ));
        let edges = &self.edges;
        // Sweep along x: edges sorted by their leftmost x (ties by index: every key is
        // distinct, so any sort gives this order); each edge meets only the edges that start
        // before it ends (most of the n²/2 pairs are never looked at).
        self.keys.clear();
        self.keys.extend(
            edges
                .iter()
                .enumerate()
                .map(|(k, e)| u128::from(total_order_key(e.min.x)) << 64 | k as u128),
        );
        self.keys.sort();
        self.sweep.clear();
        self.sweep.extend(self.keys.iter().map(|&key| {
            let edge = key as u64 as usize;
            SweepBox { min: edges[edge].min, max: edges[edge].max, edge }
        }));
        let adjacent = |i: usize, j: usize| j == i + 1 || (i == 0 && j + 1 == n);
        found.clear();
        for (k, a) in self.sweep.iter().enumerate() {
            for b in &self.sweep[k + 1..] {
                if b.min.x > a.max.x {
                    break;
                }
                let (i, j) = (a.edge.min(b.edge), a.edge.max(b.edge));
                if a.max.y < b.min.y || b.max.y < a.min.y || adjacent(i, j) {
                    continue;
                }
                match crossing(&edges[i], i, &edges[j], j) {
                    Some(Some(_)) if found.len() == MAX_CROSSINGS => {
                        self.over_limit = true;
                        return false;
                    }
                    Some(Some(crossing)) => found.push(crossing),
                    Some(None) => {}
                    None => return false,
                }
            }
        }
        distinct_positions(found, edges, &mut self.positions)
    }
}

/// The bits of `x` as an integer that orders like [`f64::total_cmp`] (negative values have
/// all bits flipped, the others the sign bit set), so that keys sort as plain integers.
fn total_order_key(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 { !bits } else { bits | 1 << 63 }
}

/// Side of a point relative to an oriented line: `cross` = (line direction) × (point −
/// line start), `length` = |line direction|.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    Left,
    Right,
    TooClose,
}

fn side(cross: f64, length: f64) -> Side {
    // NaN-safe: anything that is not clearly away from the line is too close.
    if cross.abs() > GENERICITY_TOLERANCE * length {
        if cross > 0.0 { Side::Left } else { Side::Right }
    } else {
        Side::TooClose
    }
}

/// The crossing of edges `p` (index `i`) and `q` (index `j`): `Some(None)` if they do not
/// cross, `None` if the answer or the heights are within the margin (not generic).
fn crossing(p: &Edge, i: usize, q: &Edge, j: usize) -> Option<Option<Crossing>> {
    let (r, s) = (p.end - p.start, q.end - q.start);
    let (r_length, s_length) = (r.length(), s.length());
    let o1 = r.perp_dot(q.start - p.start);
    let o2 = r.perp_dot(q.end - p.start);
    let o3 = s.perp_dot(p.start - q.start);
    let o4 = s.perp_dot(p.end - q.start);
    let sides = [side(o1, r_length), side(o2, r_length), side(o3, s_length), side(o4, s_length)];
    let same = |x: Side, y: Side| x == y && x != Side::TooClose;
    if same(sides[0], sides[1]) || same(sides[2], sides[3]) {
        return Some(None);
    }
    if sides.contains(&Side::TooClose) {
        return None;
    }
    let t = o3 / (o3 - o4);
    let u = o1 / (o1 - o2);
    let height_p = p.start_height + t * (p.end_height - p.start_height);
    let height_q = q.start_height + u * (q.end_height - q.start_height);
    if (height_p - height_q).abs() <= GENERICITY_TOLERANCE {
        return None;
    }
    let (position_p, position_q) = (i as f64 + t, j as f64 + u);
    let crossing = if height_p > height_q {
        Crossing { over: position_p, under: position_q, positive: r.perp_dot(s) > 0.0 }
    } else {
        Crossing { over: position_q, under: position_p, positive: s.perp_dot(r) > 0.0 }
    };
    Some(Some(crossing))
}

/// Whether no two crossings lie within the margin of each other along the same edge (which
/// would make their order, hence the diagram, unreliable); `positions` is scratch.
fn distinct_positions(crossings: &[Crossing], edges: &[Edge], positions: &mut Vec<f64>) -> bool {
    positions.clear();
    positions.extend(crossings.iter().flat_map(|c| [c.over, c.under]));
    positions.sort_unstable_by(f64::total_cmp);
    positions.windows(2).all(|pair| {
        let edge = pair[0].floor();
        // A position is `edge index + t` with t strictly inside (0, 1) (see `side`'s margin).
        let length = edges.get(edge as usize).map_or(0.0, |e| e.start.distance(e.end));
        edge != pair[1].floor() || (pair[1] - pair[0]) * length > GENERICITY_TOLERANCE
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_order_keys_sort_like_total_cmp() {
        let mut values =
            [3.5, -0.0, 0.0, -1e300, f64::MIN_POSITIVE, -f64::MIN_POSITIVE, 1e-300, -2.0];
        let mut keys: Vec<u64> = values.iter().map(|&x| total_order_key(x)).collect();
        values.sort_by(f64::total_cmp);
        keys.sort_unstable();
        assert_eq!(keys, values.map(total_order_key));
    }

    #[test]
    fn a_square_with_a_crossing_diagonal_is_found_and_degenerate_views_rejected() {
        // A bow-tie: edges 0 (0,0,0)→(1,1,1) and 2 (1,0,0)→(0,1,0) cross above (0.5, 0.5).
        let bow_tie = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let (mut projector, mut found) = (Projector::default(), Vec::new());
        assert!(projector.crossings(&bow_tie, DVec3::Z, &mut found), "generic");
        assert_eq!(found.len(), 1);
        assert!((found[0].over - 0.5).abs() < 1e-12 && (found[0].under - 2.5).abs() < 1e-12);
        // Seen along x, vertices 0 and 2 project to the same point.
        assert!(!projector.crossings(&bow_tie, DVec3::X, &mut found));
    }
}
