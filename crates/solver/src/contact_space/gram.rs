//! The Gram product W_R = Y_RᵀY_R of the contact space, by column blocks that skip the
//! columns' zero tails, and its lower triangle mirrored from the upper.

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par};

use crate::error::SolverError;
use crate::problem::Problem;

/// Columns per block of the product W = YᵀY.
pub(super) const W_BLOCK: usize = 96;

/// W_R's upper triangle (`w`, resized to p × p) from Y_R (`y`: its p columns by decreasing
/// `support`, or the same with ranges compressed), by column blocks [a, b):
/// W[..b, a..b] = Y[..e_a, ..b]ᵀY[..e_a, a..b] (e_a, the block's largest support, bounds every
/// product in it), polling the stop flag before each block, and between chunks of the block's
/// rows when it reads more than `polled_entries` entries of Y.
pub(super) fn form_w(
    w: &mut Mat<f64>,
    (y, support): (MatRef<'_, f64>, &[usize]),
    polled_entries: usize,
    problem: &Problem<'_>,
) -> Result<(), SolverError> {
    let m = support.len();
    w.resize_with(m, m, |_, _| 0.0);
    for a in (0..m).step_by(W_BLOCK) {
        problem.check_stop()?;
        let b = (a + W_BLOCK).min(m);
        let rows_used = support[a];
        let right = y.submatrix(0, a, rows_used, b - a);
        // W's rows [c, d) of the block: all at once, or in polled chunks when large.
        let chunk = if rows_used * b > polled_entries { W_BLOCK } else { b };
        for c in (0..b).step_by(chunk) {
            let d = (c + chunk).min(b);
            if c > 0 {
                problem.check_stop()?;
            }
            let left = y.submatrix(0, c, rows_used, d - c);
            let target = w.as_mut().submatrix_mut(c, a, d - c, b - a);
            matmul(target, Accum::Replace, left.transpose(), right, 1.0, Par::Seq);
        }
    }
    Ok(())
}

/// Side of the square tiles in which [`mirror_upper`] copies (cache-sized).
const MIRROR_TILE: usize = 32;

/// Copies the upper triangle of the square `w` onto its lower one, tile by tile so that the
/// transposed reads stay in cache.
pub(super) fn mirror_upper(w: &mut Mat<f64>) {
    let p = w.ncols();
    for tile_j in (0..p).step_by(MIRROR_TILE) {
        for tile_i in (0..=tile_j).step_by(MIRROR_TILE) {
            for j in tile_j..(tile_j + MIRROR_TILE).min(p) {
                for i in tile_i..(tile_i + MIRROR_TILE).min(j) {
                    w[(j, i)] = w[(i, j)];
                }
            }
        }
    }
}
