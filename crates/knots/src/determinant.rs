//! Exact determinant of a matrix pencil A + tB over ℤ, as a polynomial in t.
//!
//! The reduced Alexander matrix is such a pencil (entries 1 − t, t, −1 and their sums), and
//! its determinant is ±tᵏΔ(t). Expanding the determinant symbolically, or by fraction-free
//! elimination over ℤ[t], costs O(m⁵) on an m×m matrix; evaluating at m + 1 points and
//! interpolating costs O(m⁴). Here it costs O(m³), all in 𝔽ₚ ([`Residue`]):
//!
//! 1. pick a shift a (a = 1 first) with A + aB invertible; then with s = t − a,
//!    det(A + tB) = det(A + aB) · det(I + sC), C = (A + aB)⁻¹B (Gauss–Jordan, O(m³));
//! 2. det(I + sC) = Σₖ eₖ(C) sᵏ, where χ(x) = det(xI − C) = Σₖ (−1)ᵏ eₖ(C) x^(m−k) is the
//!    characteristic polynomial of C, computed by reduction to Hessenberg form and the
//!    Hessenberg recurrence (Cohen, *A Course in Computational Algebraic Number Theory*,
//!    Alg. 2.2.9), O(m³);
//! 3. substitute s = t − a back (Horner, O(m²)) and map each residue to the integer in
//!    (−p/2, p/2].
//!
//! The result is exact whenever every coefficient of det(A + tB) is below (p − 1)/2 ≈
//! 1.15·10¹⁸ in magnitude. For an Alexander matrix the shift a = 1 always works, because
//! its reduced matrix at t = 1 has determinant ±Δ(1) = ±1.

use crate::modular::Residue;

/// Coefficients of t⁰, t¹, …, tᵐ of det(A + tB) for the m×m integer matrices `a` and `b`
/// (row-major, `size` = m). All zero if the determinant vanishes identically mod p. See the
/// module documentation for the method and its range of exactness.
pub(crate) fn pencil_determinant(a: &[i64], b: &[i64], size: usize) -> Vec<i64> {
    let a: Vec<Residue> = a.iter().map(|&x| Residue::from_i64(x)).collect();
    let b: Vec<Residue> = b.iter().map(|&x| Residue::from_i64(x)).collect();
    // A non-zero polynomial of degree ≤ m has at most m roots, so one of m + 1 shifts works.
    (1..=size as i64 + 1)
        .find_map(|shift| shifted_determinant(&a, &b, size, Residue::from_i64(shift)))
        .unwrap_or_else(|| vec![Residue::ZERO; size + 1])
        .into_iter()
        .map(Residue::to_symmetric)
        .collect()
}

/// det(A + tB) mod p by the expansion about t = `shift`, or `None` if A + shift·B is singular.
fn shifted_determinant(
    a: &[Residue],
    b: &[Residue],
    m: usize,
    shift: Residue,
) -> Option<Vec<Residue>> {
    let (c, det_shifted) = solve(a, b, m, shift)?;
    let chi = characteristic_polynomial(c, m);
    // Horner in s = t − shift over the coefficients eₖ = (−1)ᵏ χ[m − k], highest k first;
    // `result ← result · (t − shift) + eₖ · det(A + shift·B)`.
    let mut result = vec![Residue::ZERO; m + 1];
    for k in (0..=m).rev() {
        for i in (0..m).rev() {
            result[i + 1] = result[i] - shift * result[i + 1];
        }
        result[0] = -(shift * result[0]);
        let e = if k % 2 == 0 { chi[m - k] } else { -chi[m - k] };
        result[0] += e * det_shifted;
    }
    Some(result)
}

/// C = (A + shift·B)⁻¹B and det(A + shift·B) by Gauss–Jordan elimination of the augmented
/// matrix [A + shift·B | B]; `None` if A + shift·B is singular.
fn solve(
    a: &[Residue],
    b: &[Residue],
    m: usize,
    shift: Residue,
) -> Option<(Vec<Residue>, Residue)> {
    let width = 2 * m;
    let mut augmented = vec![Residue::ZERO; m * width];
    for row in 0..m {
        for col in 0..m {
            let (x, y) = (a[row * m + col], b[row * m + col]);
            augmented[row * width + col] = x + shift * y;
            augmented[row * width + m + col] = y;
        }
    }
    let mut determinant = Residue::ONE;
    for col in 0..m {
        let pivot = (col..m).find(|&row| !augmented[row * width + col].is_zero())?;
        if pivot != col {
            swap_rows(&mut augmented, width, pivot, col);
            determinant = -determinant;
        }
        let pivot_value = augmented[col * width + col];
        determinant = determinant * pivot_value;
        let inverse = pivot_value.inverse()?;
        for x in &mut augmented[col * width + col..(col + 1) * width] {
            *x = *x * inverse;
        }
        for row in (0..m).filter(|&row| row != col) {
            let factor = augmented[row * width + col];
            if factor.is_zero() {
                continue;
            }
            for k in col..width {
                let delta = factor * augmented[col * width + k];
                augmented[row * width + k] -= delta;
            }
        }
    }
    let c = (0..m).flat_map(|row| augmented[row * width + m..(row + 1) * width].to_vec()).collect();
    Some((c, determinant))
}

/// Coefficients of x⁰ … xᵐ of det(xI − H) for the m×m matrix `h` (consumed): similarity
/// reduction to upper Hessenberg form, then the recurrence
/// pₖ = (x − hₖₖ)pₖ₋₁ − Σᵢ₌₁^(k−1) hₖ₋ᵢ,ₖ (hₖ,ₖ₋₁ ⋯ hₖ₋ᵢ₊₁,ₖ₋ᵢ) pₖ₋ᵢ₋₁ (1-based indices).
fn characteristic_polynomial(mut h: Vec<Residue>, m: usize) -> Vec<Residue> {
    for j in 0..m.saturating_sub(2) {
        let Some(pivot) = (j + 1..m).find(|&i| !h[i * m + j].is_zero()) else {
            continue;
        };
        if pivot != j + 1 {
            swap_rows(&mut h, m, pivot, j + 1);
            for row in 0..m {
                h.swap(row * m + pivot, row * m + j + 1);
            }
        }
        let Some(inverse) = h[(j + 1) * m + j].inverse() else {
            continue;
        };
        // H ← L H L⁻¹ with L = Πᵢ (row i −= uᵢ row j+1): the factors commute, so all row
        // operations go first, then all column operations (column j+1 += Σᵢ uᵢ column i),
        // done row by row for contiguous access.
        let u: Vec<Residue> = (j + 2..m).map(|i| h[i * m + j] * inverse).collect();
        for (i, &factor) in (j + 2..m).zip(&u) {
            if factor.is_zero() {
                continue;
            }
            for k in j..m {
                let delta = factor * h[(j + 1) * m + k];
                h[i * m + k] -= delta;
            }
        }
        for row in h.chunks_exact_mut(m) {
            row[j + 1] += Residue::dot(&row[j + 2..], &u);
        }
    }
    let entry = |row: usize, col: usize| h[(row - 1) * m + col - 1];
    let mut p: Vec<Vec<Residue>> = vec![vec![Residue::ONE]];
    for k in 1..=m {
        let mut next = vec![Residue::ZERO; k + 1];
        for (i, &c) in p[k - 1].iter().enumerate() {
            next[i + 1] += c;
            next[i] -= entry(k, k) * c;
        }
        let mut product = Residue::ONE;
        for i in 1..k {
            product = product * entry(k - i + 1, k - i);
            let factor = product * entry(k - i, k);
            for (x, &c) in next.iter_mut().zip(&p[k - i - 1]) {
                *x -= factor * c;
            }
        }
        p.push(next);
    }
    p.pop().unwrap_or_else(|| vec![Residue::ONE])
}

/// Swaps rows `i` and `j` of a row-major matrix with `width` columns.
fn swap_rows(matrix: &mut [Residue], width: usize, i: usize, j: usize) {
    let (low, high) = (i.min(j), i.max(j));
    let (head, tail) = matrix.split_at_mut(high * width);
    head[low * width..(low + 1) * width].swap_with_slice(&mut tail[..width]);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// det(A + tB) at integer t by Laplace expansion (small matrices only).
    fn brute_force(a: &[i64], b: &[i64], m: usize, t: i64) -> i128 {
        let matrix: Vec<i128> = a.iter().zip(b).map(|(&x, &y)| i128::from(x + t * y)).collect();
        laplace(&matrix, m)
    }

    fn laplace(matrix: &[i128], m: usize) -> i128 {
        if m == 0 {
            return 1;
        }
        (0..m)
            .map(|col| {
                let minor: Vec<i128> = (1..m)
                    .flat_map(|row| (0..m).filter(move |&c| c != col).map(move |c| (row, c)))
                    .map(|(row, c)| matrix[row * m + c])
                    .collect();
                let sign = if col % 2 == 0 { 1 } else { -1 };
                sign * matrix[col] * laplace(&minor, m - 1)
            })
            .sum()
    }

    fn evaluate(coefficients: &[i64], t: i64) -> i128 {
        coefficients.iter().rev().fold(0, |acc, &c| acc * i128::from(t) + i128::from(c))
    }

    #[test]
    fn matches_laplace_expansion_on_pseudo_random_pencils() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % 5) as i64 - 2
        };
        for m in 0..=6 {
            for _ in 0..5 {
                let a: Vec<i64> = (0..m * m).map(|_| next()).collect();
                let b: Vec<i64> = (0..m * m).map(|_| next()).collect();
                let coefficients = pencil_determinant(&a, &b, m);
                assert_eq!(coefficients.len(), m + 1);
                for t in -3..=3 {
                    assert_eq!(evaluate(&coefficients, t), brute_force(&a, &b, m, t), "m={m}");
                }
            }
        }
    }

    #[test]
    fn shifts_past_a_singular_a_plus_b_and_handles_zero() {
        // A + B = 0; det(A + tB) = (1 − t)(t − 1) = −1 + 2t − t².
        assert_eq!(pencil_determinant(&[1, 0, 0, -1], &[-1, 0, 0, 1], 2), vec![-1, 2, -1]);
        assert_eq!(pencil_determinant(&[1, 1, 1, 1], &[1, 1, 1, 1], 2), vec![0, 0, 0]);
        assert_eq!(pencil_determinant(&[], &[], 0), vec![1]);
    }
}
