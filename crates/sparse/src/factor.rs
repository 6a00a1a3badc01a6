//! The tree-structured factorisation of the maximal-coordinate velocity system
//! (`docs/physics.md`, "Sparse maximal-coordinate backend").
//!
//! Unknowns: the world twist `V_i` of every body, the joint rates `q̇_c` and a 6-vector
//! multiplier `μ_c` per joint for the joint constraint `V_c − V_p(c) − S_c q̇_c = 0`
//! (`V_p = 0` for a root). The step's system is the optimality condition of
//!
//! `min Σ_i ½ V_iᵀ Ĩ_i V_i + Σ_c (½ q̇_cᵀ K̃_c q̇_c − q̇_cᵀ f̃_c)` subject to the joint
//! constraints, with `Ĩ_i = I_i + h C_i` (body inertia plus the implicit point dampers) and
//! `K̃ = hD + h²K` (diagonal). Eliminating the twists gives back the reduced
//! `M̃ q̇ = (Jᵀ Ĩ J + K̃) q̇ = f̃` of the dense path exactly.
//!
//! Eliminating the unknowns of each body and joint leaf to root is an LDLᵀ factorisation of
//! the saddle-point matrix in an order with no fill (the elimination tree is the body
//! tree, so the symbolic factorisation is the parent array, fixed per model). Its numeric
//! part is the articulated-inertia recursion, leaf to root:
//!
//! - `Iᴬ_i = Ĩ_i + Σ_{children k} (Iᴬ_k − Ū_k Ū_kᵀ)`,
//! - `U_c = Iᴬ_c S_c`, `D_c = S_cᵀ U_c + K̃_c = R_c R_cᵀ` (Cholesky, `n_c ≤ 6`),
//!   `Ū_c = U_c R_c⁻ᵀ`.
//!
//! It gives the square-root split `M̃⁻¹ = Lᵀ⁻¹ L⁻¹` with `L⁻¹ = R⁻¹A`, applied in O(bodies):
//!
//! - `y = L⁻¹f` (leaf to root): `u_c = f_c − S_cᵀ p_c`, `y_c = R_c⁻¹ u_c`,
//!   `p_parent += p_c + Ū_c y_c`;
//! - `x = L⁻ᵀy` (root to leaf): `x_c = R_c⁻ᵀ (y_c − Ū_cᵀ a_p)`, `a_c = a_p + S_c x_c`
//!   (`a_p` the parent's twist, 0 at a root).
//!
//! The second pass is the transpose of the first, so `M̃⁻¹ = (L⁻¹)ᵀ L⁻¹` and the
//! contact-space solver can use `Y = L⁻¹Cᵀ`, `W = YᵀY` exactly as with a dense Cholesky
//! factor.

use std::cell::RefCell;
use std::ops::Range;

use faer::MatMut;
use hagfish_solver::SolverError;
use hagfish_tree::{Data, Model, RigidInertia, Spatial};

use crate::block::{Block6, to_array};
use crate::error::SparseError;

/// Largest number of DOFs of one joint (a free joint).
pub(crate) const MAX_JOINT_DOFS: usize = 6;

/// Most columns that one leaf-to-root pass solves together
/// ([`TreeFactor::solve_lower_lanes`]): the factor is read once for all of them.
pub(crate) const LANES: usize = 4;

/// The factor of one step's maximal-coordinate system. Create once per model with
/// [`TreeFactor::new`] (the symbolic part), then per step [`TreeFactor::assemble`] and
/// [`TreeFactor::factor`]; it never allocates after construction.
#[derive(Debug)]
pub struct TreeFactor {
    /// Parent body of each body (`None` for a root): the elimination tree.
    parents: Vec<Option<usize>>,
    /// The DOFs of each body's joint.
    dofs: Vec<Range<usize>>,
    /// The body whose joint holds each DOF.
    dof_bodies: Vec<usize>,
    /// World joint axes `s_a` (one per DOF), copied by `assemble`.
    axes: Vec<Spatial>,
    /// `Ĩ_i = I_i + h C_i` per body.
    inertias: Vec<RigidInertia>,
    /// `K̃_a = h d_a + h² k_a` per DOF.
    joint_diagonal: Vec<f64>,
    /// Articulated inertias (scratch of `factor`).
    articulated: Vec<Block6>,
    /// `Ū_c = U_c R_c⁻ᵀ`, one column per DOF.
    gains: Vec<Spatial>,
    /// Row `a` of the joint's Cholesky factor `R_c` (entries `R_ab` for the joint's DOFs b ≤ a,
    /// indexed from the joint's first DOF), one row per DOF.
    pivots: Vec<[f64; MAX_JOINT_DOFS]>,
    /// Whether `factor` succeeded on the current assembly.
    factored: bool,
    /// Per-body spatial scratch of the passes.
    scratch: RefCell<Vec<Spatial>>,
    /// Per-body scratch of the batched leaf-to-root pass: the bias `p` of each of its K
    /// lanes, component c (in the order of [`to_array`]) of lane k of body i at
    /// `[(6i + c)K + k]`; a pass of K lanes uses (and clears) only its first 6·bodies·K
    /// entries, so a single column does not sweep the room of [`LANES`].
    lane_bias: RefCell<Vec<f64>>,
    /// Interleaved columns of the batched pass, n × [`LANES`] (see `operator.rs`).
    lane_columns: RefCell<Vec<f64>>,
    /// The number of children of each body (the chains of [`TreeFactor::wrench_span`]).
    child_counts: Vec<usize>,
    /// The highest-numbered child of each body (`None` for a leaf): the first one the
    /// leaf-to-root pass eliminates, which starts its parent's articulated inertia.
    last_children: Vec<Option<usize>>,
    /// The six interleaved columns of [`TreeFactor::wrench_span`] (n entries).
    span_lanes: RefCell<Vec<[f64; 6]>>,
}

impl TreeFactor {
    /// The symbolic factorisation of `model`: its elimination tree (the parent array) and
    /// buffers for every numeric quantity. Fails for a joint with more than 6 DOFs.
    pub fn new(model: &Model) -> Result<Self, SparseError> {
        let (nb, n) = (model.body_count(), model.dof_count());
        let mut dofs = Vec::with_capacity(nb);
        for (body, joint) in model.joints().iter().enumerate() {
            let range = joint.dofs();
            if range.len() > MAX_JOINT_DOFS {
                return Err(SparseError::TooManyJointDofs { body, dofs: range.len() });
            }
            dofs.push(range);
        }
        let (mut child_counts, mut last_children) = (vec![0; nb], vec![None; nb]);
        for (child, joint) in model.joints().iter().enumerate() {
            if let Some(parent) = joint.parent {
                child_counts[parent] += 1;
                last_children[parent] = Some(child);
            }
        }
        Ok(Self {
            parents: model.joints().iter().map(|j| j.parent).collect(),
            dofs,
            dof_bodies: model.dof_joint().to_vec(),
            axes: vec![Spatial::ZERO; n],
            inertias: vec![RigidInertia::ZERO; nb],
            joint_diagonal: vec![0.0; n],
            articulated: vec![Block6::ZERO; nb],
            gains: vec![Spatial::ZERO; n],
            pivots: vec![[0.0; MAX_JOINT_DOFS]; n],
            factored: false,
            scratch: RefCell::new(vec![Spatial::ZERO; nb]),
            lane_bias: RefCell::new(vec![0.0; 6 * nb * LANES]),
            lane_columns: RefCell::new(vec![0.0; n * LANES]),
            child_counts,
            last_children,
            span_lanes: RefCell::new(vec![[0.0; 6]; n]),
        })
    }

    /// Number of reduced DOFs n.
    pub fn dofs(&self) -> usize {
        self.axes.len()
    }

    /// Whether [`factor`](Self::factor) succeeded since the last
    /// [`assemble`](Self::assemble).
    pub fn is_factored(&self) -> bool {
        self.factored
    }

    /// Assembles the system of a step of size `h` (s) from the kinematics and the applied
    /// point dampers in `data`: `Ĩ_i = I_i + h C_i`, `K̃_a = h d_a + h² k_a` (with this step's
    /// joint servos, `Data::joint_diagonal`) and the axes `s_a`. `model` must be the one given
    /// to [`new`](Self::new). O(bodies).
    pub fn assemble(&mut self, model: &Model, data: &Data, h: f64) {
        self.axes.copy_from_slice(&data.axes);
        for ((tilde, inertia), damping) in
            self.inertias.iter_mut().zip(&data.inertias).zip(&data.applied_damping)
        {
            *tilde = *inertia;
            tilde.add_scaled(damping, h);
        }
        for (a, (k, dof)) in self.joint_diagonal.iter_mut().zip(model.dofs()).enumerate() {
            *k = data.joint_diagonal(dof, a, h);
        }
        self.factored = false;
    }

    /// The numeric factorisation (module docs), leaf to root, O(bodies). Fails, as the dense
    /// Cholesky does, with the first DOF whose pivot `D_c` is not positive (a body without
    /// inertia on a joint without damping or stiffness).
    pub fn factor(&mut self) -> Result<(), SolverError> {
        self.factored = false;
        for body in (0..self.parents.len()).rev() {
            let range = self.dofs[body].clone();
            let start = range.start;
            // A body's block starts as its inertia Ĩ_i where it is first written, in this one
            // pass: a leaf's here, a parent's when its highest-numbered child (the first
            // eliminated) adds to it below.
            if self.last_children[body].is_none() {
                self.articulated[body] = Block6::from_inertia(&self.inertias[body]);
            }
            // The body's block by reference (its parent's, earlier in the list, is the only
            // one written below): no 6 × 6 copy per body.
            let (ancestors, rest) = self.articulated.split_at_mut(body);
            let articulated = &rest[0];
            let mut unreduced = [Spatial::ZERO; MAX_JOINT_DOFS];
            for (u, a) in unreduced.iter_mut().zip(range.clone()) {
                *u = articulated.apply(&self.axes[a]);
            }
            // D_ij = s_iᵀ U_j + δ_ij K̃_i = Σ_c R_ic R_jc, row by row.
            for (i, a) in range.clone().enumerate() {
                let mut row = [0.0; MAX_JOINT_DOFS];
                for j in 0..=i {
                    let mut value = self.axes[a].dot(&unreduced[j]);
                    if j == i {
                        value += self.joint_diagonal[a];
                    }
                    let other = if j == i { row } else { self.pivots[start + j] };
                    value -= row[..j].iter().zip(&other[..j]).map(|(x, y)| x * y).sum::<f64>();
                    if j < i {
                        row[j] = value / self.pivots[start + j][j];
                    } else if value > 0.0 && value.is_finite() {
                        row[i] = value.sqrt();
                    } else {
                        return Err(SolverError::NotPositiveDefinite { pivot: a });
                    }
                }
                self.pivots[a] = row;
                // Ū_i = (U_i − Σ_{c<i} Ū_c R_ic) / R_ii.
                let mut gain = unreduced[i];
                for (c, r) in row[..i].iter().enumerate() {
                    gain = gain.add_scaled(&self.gains[start + c], -r);
                }
                self.gains[a] = gain * (1.0 / row[i]);
            }
            if let Some(parent) = self.parents[body] {
                if self.last_children[parent] == Some(body) {
                    ancestors[parent] = Block6::from_inertia(&self.inertias[parent]);
                }
                ancestors[parent].add_downdated(articulated, &self.gains[range]);
            }
        }
        self.factored = true;
        Ok(())
    }

    /// `f ← L⁻¹ f` (one column of length n; module docs). Requires a successful
    /// [`factor`](Self::factor).
    pub fn solve_lower_column(&self, f: &mut [f64]) {
        let (lanes, _) = f.as_chunks_mut::<1>();
        self.solve_lower_lanes(lanes, lanes.len());
    }

    /// Where `L⁻¹` keeps trailing zeros: for an f that vanishes from DOF `end` on, `L⁻¹f`
    /// vanishes from the end of the DOFs of the body holding DOF `end − 1` on (from 0 when
    /// `end` is 0). The leaf-to-root pass forms a body's entries from its own and its
    /// subtree's entries, and every later body (its subtree with it: children come after
    /// parents) holds DOFs from `end` on only.
    pub(crate) fn lower_support(&self, end: usize) -> usize {
        end.checked_sub(1).map_or(0, |last| self.dofs[self.dof_bodies[last]].end)
    }

    /// The leaf-to-root pass `x ← L⁻¹x` (module docs) on K ≤ [`LANES`] columns at once,
    /// interleaved (entry a of column k at `x[a][k]`), for columns that vanish from DOF
    /// `support` on, a value of [`lower_support`](Self::lower_support) (n for any columns):
    /// only the bodies holding the DOFs `..support` are visited (the later entries are zero
    /// and stay zero), so `x` needs only those entries. Each lane goes through the operations
    /// of a single column in the same order, so its result does not depend on the others.
    pub(crate) fn solve_lower_lanes<const K: usize>(&self, x: &mut [[f64; K]], support: usize) {
        const { assert!(K <= LANES) };
        let bodies = support.checked_sub(1).map_or(0, |last| self.dof_bodies[last] + 1);
        let mut storage = self.lane_bias.borrow_mut();
        let (bias, _) = storage[..6 * bodies * K].as_chunks_mut::<K>();
        let (bias, _) = bias.as_chunks_mut::<6>();
        bias.fill([[0.0; K]; 6]);
        for body in (0..bodies).rev() {
            let contribution = self.eliminate(body, &mut x[self.dofs[body].clone()], bias[body]);
            if let Some(parent) = self.parents[body] {
                for (b, c) in bias[parent].iter_mut().zip(&contribution) {
                    for k in 0..K {
                        b[k] += c[k];
                    }
                }
            }
        }
    }

    /// One body of the leaf-to-root pass on K lanes: its joint's entries `joint` (K lanes
    /// each) ← `y_c = R_c⁻¹(f_c − S_cᵀp)` for the bias `p` its children passed, and returns
    /// `p + Ū_c y_c`, what it passes to its parent (module docs).
    fn eliminate<const K: usize>(
        &self,
        body: usize,
        joint: &mut [[f64; K]],
        p: [[f64; K]; 6],
    ) -> [[f64; K]; 6] {
        let mut contribution = p;
        for (i, a) in self.dofs[body].clone().enumerate() {
            let (axis, gain, row) =
                (to_array(&self.axes[a]), to_array(&self.gains[a]), &self.pivots[a]);
            let (solved, rest) = joint.split_at_mut(i);
            let entry = &mut rest[0];
            // y_a = (f_a − s_aᵀp − Σ_{c<a} R_ac y_c) / R_aa, the sum from −0 as `Sum` does.
            let mut done = [-0.0; K];
            for (r, y) in row.iter().zip(solved.iter()) {
                for k in 0..K {
                    done[k] += r * y[k];
                }
            }
            for k in 0..K {
                let twist = (axis[0] * p[0][k] + axis[1] * p[1][k] + axis[2] * p[2][k])
                    + (axis[3] * p[3][k] + axis[4] * p[4][k] + axis[5] * p[5][k]);
                entry[k] = (entry[k] - twist - done[k]) / row[i];
            }
            for (c, g) in contribution.iter_mut().zip(&gain) {
                for k in 0..K {
                    c[k] += g * entry[k];
                }
            }
        }
        contribution
    }

    /// The wrench span of L⁻¹ on the DOFs `range` (`hagfish_solver::FactoredMass::wrench_span`):
    /// when `range` holds the whole joints of bodies b₀..=b₁ that form a chain (each the
    /// parent of the next, none but b₁ with children elsewhere), writes into `out`
    /// (`range.len()` × 6) the pass over those bodies of f = 0 from the six unit biases
    /// p = e_k entering b₁, and returns true. On such a range a column with c_a = s_aᵀF has
    /// `y_c = −R_c⁻¹S_cᵀ(p − F)` and passes `(p − F) + Ū_c y_c` on: a linear function of the
    /// one six-vector p − F entering b₁, so it lies in the span of these six.
    pub(crate) fn wrench_span(&self, range: Range<usize>, mut out: MatMut<'_, f64>) -> bool {
        let (Some(&first), Some(&last)) = (
            self.dof_bodies.get(range.start),
            range.end.checked_sub(1).and_then(|e| self.dof_bodies.get(e)),
        ) else {
            return false;
        };
        let whole_joints =
            self.dofs[first].start == range.start && self.dofs[last].end == range.end;
        let chain = (first + 1..=last).all(|body| self.parents[body] == Some(body - 1))
            && (first..last).all(|body| self.child_counts[body] == 1);
        if !whole_joints || !chain || out.nrows() != range.len() || out.ncols() != 6 {
            return false;
        }
        let mut storage = self.span_lanes.borrow_mut();
        let lanes = &mut storage[..range.len()];
        lanes.fill([0.0; 6]);
        let mut p = [[0.0; 6]; 6];
        for (k, component) in p.iter_mut().enumerate() {
            component[k] = 1.0;
        }
        for body in (first..=last).rev() {
            let dofs = self.dofs[body].clone();
            p = self.eliminate(
                body,
                &mut lanes[dofs.start - range.start..dofs.end - range.start],
                p,
            );
        }
        for (a, lane) in lanes.iter().enumerate() {
            for (k, value) in lane.iter().enumerate() {
                out[(a, k)] = *value;
            }
        }
        true
    }

    /// The interleaved columns of the batched pass (n × [`LANES`] entries).
    pub(crate) fn lane_columns(&self) -> std::cell::RefMut<'_, Vec<f64>> {
        self.lane_columns.borrow_mut()
    }

    /// `y ← L⁻ᵀ y` (one column of length n; module docs). Requires a successful
    /// [`factor`](Self::factor).
    pub fn solve_upper_column(&self, y: &mut [f64]) {
        let mut twists = self.scratch.borrow_mut();
        for body in 0..self.parents.len() {
            let range = self.dofs[body].clone();
            let start = range.start;
            let parent_twist = self.parents[body].map_or(Spatial::ZERO, |p| twists[p]);
            for a in range.clone() {
                y[a] -= self.gains[a].dot(&parent_twist);
            }
            for a in range.clone().rev() {
                let done: f64 = (a + 1..range.end).map(|c| self.pivots[c][a - start] * y[c]).sum();
                y[a] = (y[a] - done) / self.pivots[a][a - start];
            }
            let mut twist = parent_twist;
            for a in range {
                twist = twist.add_scaled(&self.axes[a], y[a]);
            }
            twists[body] = twist;
        }
    }

    /// `out ← M̃ x = Jᵀ Ĩ J x + K̃ x` in O(bodies): twists root to leaf, momenta `Ĩ_i V_i`,
    /// subtree sums leaf to root, projected on the axes. Needs only
    /// [`assemble`](Self::assemble).
    pub fn apply(&self, x: &[f64], out: &mut [f64]) {
        let mut work = self.scratch.borrow_mut();
        for body in 0..self.parents.len() {
            let mut twist = self.parents[body].map_or(Spatial::ZERO, |p| work[p]);
            for a in self.dofs[body].clone() {
                twist = twist.add_scaled(&self.axes[a], x[a]);
            }
            work[body] = twist;
        }
        for (momentum, inertia) in work.iter_mut().zip(&self.inertias) {
            *momentum = inertia.apply(momentum);
        }
        for body in (0..self.parents.len()).rev() {
            let sum = work[body];
            for a in self.dofs[body].clone() {
                out[a] = self.axes[a].dot(&sum) + self.joint_diagonal[a] * x[a];
            }
            if let Some(parent) = self.parents[body] {
                work[parent] += sum;
            }
        }
    }
}
