//! Problem generators shared by the integration tests and the contact-space bench.
//!
//! Values resemble the hagfish: the diagonal of M̃ spans 1e-2 … 1e4 (condition ~1e6–1e8),
//! row norms 0.1 … 40. Feasibility of the hard rows is certain: a target velocity q̇* is drawn
//! and equalities get b = cᵀq̇*, inequalities b = cᵀq̇* − gap with gap ≥ 0; a fraction of them
//! gets gap = 0 (they pass through q̇*; more of those than DOFs makes a degenerate vertex).
//! Soft rows get targets that may be unreachable.
use faer::Mat;
use hagfish_solver::{RowKind, RowSource, RowTag, Rows};

/// SplitMix64: a tiny deterministic generator (proptest draws the seed).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform integer in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.uniform() * n as f64) as usize % n.max(1)
    }

    /// Log-uniform in [low, high].
    pub fn log_uniform(&mut self, low: f64, high: f64) -> f64 {
        (low.ln() + self.uniform() * (high.ln() - low.ln())).exp()
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let u = 1.0 - self.uniform();
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * self.uniform()).cos()
    }
}

/// M̃ = S B S with B = AᵀA/n + 0.1 I (A n × n standard normal) and S = diag(√dᵢ), dᵢ
/// log-uniform in [1e-2, 1e4].
pub fn random_mass(rng: &mut Rng, n: usize) -> Mat<f64> {
    let a = Mat::from_fn(n, n, |_, _| rng.normal());
    let scale: Vec<f64> = (0..n).map(|_| rng.log_uniform(1e-2, 1e4).sqrt()).collect();
    let b = a.transpose() * &a;
    Mat::from_fn(n, n, |i, j| {
        let bij = b[(i, j)] / n as f64 + if i == j { 0.1 } else { 0.0 };
        scale[i] * bij * scale[j]
    })
}

/// A random row: 30 % a joint-limit row ±eₖ, else a contact-like row (entries of random sign
/// and magnitude 0.1 … 1 on a window of consecutive DOFs) with norm log-uniform in [0.1, 40].
pub fn random_row(rng: &mut Rng, n: usize) -> Vec<f64> {
    let mut row = vec![0.0; n];
    if rng.uniform() < 0.3 {
        row[rng.below(n)] = if rng.uniform() < 0.5 { 1.0 } else { -1.0 };
        return row;
    }
    let start = rng.below(n);
    let end = start + 1 + rng.below(n - start);
    for value in &mut row[start..end] {
        let magnitude = 0.1 + 0.9 * rng.uniform();
        *value = if rng.uniform() < 0.5 { magnitude } else { -magnitude };
    }
    let norm = row.iter().map(|v| v * v).sum::<f64>().sqrt().max(1e-300);
    let target = rng.log_uniform(0.1, 40.0);
    row.iter_mut().for_each(|v| *v *= target / norm);
    row
}

/// Row counts of a generated problem.
#[derive(Debug, Clone, Copy)]
pub struct Shape {
    pub dofs: usize,
    pub equalities: usize,
    pub inequalities: usize,
    pub soft: usize,
    /// Probability that a row repeats an earlier one (same c and b, or both scaled).
    pub duplicates: f64,
    /// Probability that an inequality passes through q̇* (gap = 0).
    pub tight: f64,
}

/// One generated problem (a drawn q̇* satisfies every hard row).
pub struct Scenario {
    pub mass: Mat<f64>,
    pub force: Vec<f64>,
    pub rows: Rows,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// A random well-posed problem of the given shape over `mass`.
pub fn scenario(rng: &mut Rng, mass: Mat<f64>, shape: Shape) -> Scenario {
    let n = shape.dofs;
    let target: Vec<f64> = (0..n).map(|_| rng.normal()).collect();
    let start: Vec<f64> = (0..n).map(|_| 3.0 * rng.normal()).collect();
    let force: Vec<f64> = (0..n).map(|i| (0..n).map(|j| mass[(i, j)] * start[j]).sum()).collect();
    let mut rows = Rows::new(n);
    let kinds = std::iter::repeat_n(0, shape.equalities)
        .chain(std::iter::repeat_n(1, shape.inequalities))
        .chain(std::iter::repeat_n(2, shape.soft));
    for code in kinds {
        // Tag = the kind code (plus one of three for inequalities), id = the row's position.
        let (kind, tag) = match code {
            0 => (RowKind::Equality, 0),
            1 => (RowKind::Inequality, 1 + rng.below(3)),
            _ => (RowKind::SoftInequality { weight: rng.log_uniform(0.1, 1e3) }, 4),
        };
        let tag = RowTag::new(u8::try_from(tag).unwrap_or(0));
        let source = RowSource::new(tag, rows.len());
        let same_kind: Vec<usize> = (0..rows.len()).filter(|&i| rows.kinds()[i] == kind).collect();
        let (row, rhs) = if !same_kind.is_empty() && rng.uniform() < shape.duplicates {
            let original = same_kind[rng.below(same_kind.len())];
            let factor = if rng.uniform() < 0.5 { 1.0 } else { rng.log_uniform(0.5, 2.0) };
            let row: Vec<f64> = rows
                .row(original)
                .map(|r| r.to_vec())
                .unwrap_or_default()
                .iter()
                .map(|c| factor * c)
                .collect();
            (row, factor * rows.rhs()[original])
        } else {
            let row = random_row(rng, n);
            let at_target = dot(&row, &target);
            let rhs = match kind {
                RowKind::Equality | RowKind::Friction { .. } => at_target,
                RowKind::Inequality if rng.uniform() < shape.tight => at_target,
                RowKind::Inequality => at_target - rng.uniform() * 2.0 * dot(&row, &row).sqrt(),
                RowKind::SoftInequality { .. } | RowKind::Compliant { .. } => {
                    at_target + rng.normal() * dot(&row, &row).sqrt()
                }
            };
            (row, rhs)
        };
        let pushed = rows.push(kind, source, rhs, &row);
        assert!(pushed.is_ok(), "generator built a row of the wrong length");
    }
    Scenario { mass, force, rows }
}
