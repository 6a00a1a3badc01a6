//! Jacobians: body twists, `J̇q̇`, and point Jacobians, all read off the world axes `s_a`.
//!
//! - Body Jacobian (body coordinates, `docs/physics.md`, "Kinematics and dynamics"): rows of body `k` are
//!   `J_k[:, a] = Ad(E_wk⁻¹) s_a` for DOFs `a` on the path of `k`, zero elsewhere, so the body
//!   twist is `φ_k = J_k q̇`.
//! - `J̇q̇` of body `k` is `Ad(E_wk⁻¹) A_k`: differentiating `φ = Ad(E⁻¹) V` gives
//!   `Ad(E⁻¹) V̇ − ad(φ) φ`, and `ad(φ) φ = 0`. It costs nothing beyond the kinematics pass.
//! - Point Jacobian of a world point `x` moving with body `k`: column `a` is
//!   `v_a + ω_a × x`, i.e. `P_k(x) = R_k Γ(x_local) J_k`.
//!
//! Run [`crate::forward_kinematics`] first.

use faer::MatMut;
use faer::reborrow::ReborrowMut;
use glam::DVec3;

use crate::data::Data;
use crate::model::Model;
use crate::spatial::Spatial;

/// Writes the 6×n body Jacobian `J_k` (angular rows first) of `body` into `out`.
pub fn body_jacobian(model: &Model, data: &Data, body: usize, mut out: MatMut<'_, f64>) {
    out.fill(0.0);
    let frame = &data.body_frames[body];
    for joint in model.path_to_root(body) {
        for a in joint.dofs() {
            let column = data.axes[a].to_body(frame);
            write_spatial(&column, out.rb_mut(), a);
        }
    }
}

/// The velocity-product term `J̇_k q̇` of `body` in body coordinates: the body acceleration
/// (angular first) when `q̈ = 0`.
pub fn body_bias_acceleration(data: &Data, body: usize) -> Spatial {
    data.bias_accelerations[body].to_body(&data.body_frames[body])
}

/// The body twist `φ_k = J_k q̇` of `body` in body coordinates.
pub fn body_twist(data: &Data, body: usize) -> Spatial {
    data.velocities[body].to_body(&data.body_frames[body])
}

/// Writes the 3×n point Jacobian of the world point `x` moving with `body` into `out`:
/// `ẋ = P q̇`.
pub fn point_jacobian(model: &Model, data: &Data, body: usize, x: DVec3, mut out: MatMut<'_, f64>) {
    out.fill(0.0);
    for joint in model.path_to_root(body) {
        for a in joint.dofs() {
            let v = data.axes[a].point_velocity(x);
            out[(0, a)] = v.x;
            out[(1, a)] = v.y;
            out[(2, a)] = v.z;
        }
    }
}

/// Adds `scale · nᵀ P_k(x)` to `row`: the rate of the distance along the world direction `n`
/// of the point `x` moving with `body`, per unit `q̇`. This is how every contact, wall and
/// thigmotaxis row is assembled, one spline weight at a time. Column `a` gets
/// `scale · (n·v_a + (x × n)·ω_a)`.
pub fn add_point_row(
    model: &Model,
    data: &Data,
    body: usize,
    x: DVec3,
    n: DVec3,
    scale: f64,
    row: &mut [f64],
) {
    let moment_arm = x.cross(n);
    for joint in model.path_to_root(body) {
        for a in joint.dofs() {
            let s = &data.axes[a];
            row[a] += scale * (n.dot(s.linear) + moment_arm.dot(s.angular));
        }
    }
}

/// Adds `Σ_k scale_k · nᵀ P_{b_k}(x_k)` to `row` for the points `(b_k, x_k, scale_k)` (at most
/// 64), in one walk from the highest-numbered body to its root instead of one walk per
/// point: [`add_point_rows_along`] with one direction.
pub fn add_point_rows(
    model: &Model,
    data: &Data,
    points: &[(usize, DVec3, f64)],
    n: DVec3,
    row: &mut [f64],
) {
    add_point_rows_along(model, data, points, [n], [row]);
}

/// Adds `Σ_k scale_k · n_jᵀ P_{b_k}(x_k)` to `rows[j]` for each direction `n_j` (a contact's
/// three base rows in one walk), for the points `(b_k, x_k, scale_k)` (at most 64), in one
/// walk from the highest-numbered body to its root instead of one walk per point and
/// direction: a DOF a on that path gets `n_j·v_a C + ((X × n_j)·ω_a)` with `C = Σ scale_k`
/// and `X = Σ scale_k x_k` over the points at or below it (the points read, and the moment
/// arms `X × n_j` formed, only at the bodies that carry a point). Once the walk has passed the
/// lowest-numbered point's body (if that is on the path), C and X no longer change, and the
/// rest of the path is added run by run over [`crate::Data::axis_components`] as
/// `s_a · (X × n_j; C n_j)`. Points whose bodies are not on the path are added one by one
/// ([`add_point_row`]). Each row gets the operations of a walk of its own, in the same order:
/// equal to the sum of the single-point rows up to rounding, and bit for bit to one call per
/// direction.
pub fn add_point_rows_along<const K: usize>(
    model: &Model,
    data: &Data,
    points: &[(usize, DVec3, f64)],
    directions: [DVec3; K],
    mut rows: [&mut [f64]; K],
) {
    let (Some(deepest), Some(shallowest)) =
        (points.iter().map(|p| p.0).max(), points.iter().map(|p| p.0).min())
    else {
        return;
    };
    if points.len() > 64 {
        for (row, n) in rows.iter_mut().zip(directions) {
            for &(body, x, scale) in points {
                add_point_row(model, data, body, x, n, scale, row);
            }
        }
        return;
    }
    // The points' bodies, deepest first: the walk looks at the points only where it reaches
    // one of them, and forms the moment arms X × n_j only where X changes.
    let mut point_bodies = [0usize; 64];
    for (slot, point) in point_bodies.iter_mut().zip(points) {
        *slot = point.0;
    }
    let point_bodies = &mut point_bodies[..points.len()];
    point_bodies.sort_unstable_by(|a, b| b.cmp(a));
    let mut reached = 0;
    let (mut total, mut moment, mut on_path) = (0.0, DVec3::ZERO, 0u64);
    // Formed at the walk's first body, the deepest point's.
    let mut moment_arms = [DVec3::ZERO; K];
    let mut next = Some(deepest);
    while let Some(body) = next {
        // The path's bodies decrease (children come after their parents): the points' bodies
        // above this one were met already or are off the path (added below, one by one).
        while point_bodies.get(reached).is_some_and(|&b| b > body) {
            reached += 1;
        }
        if point_bodies.get(reached) == Some(&body) {
            for (k, &(b, x, scale)) in points.iter().enumerate() {
                if b == body {
                    total += scale;
                    moment += scale * x;
                    on_path |= 1 << k;
                }
            }
            moment_arms = directions.map(|n| moment.cross(n));
        }
        let joint = &model.joints()[body];
        for ((row, n), moment_arm) in rows.iter_mut().zip(directions).zip(moment_arms) {
            for a in joint.dofs() {
                let s = &data.axes[a];
                row[a] += total * n.dot(s.linear) + moment_arm.dot(s.angular);
            }
        }
        next = joint.parent;
        if body == shallowest {
            break;
        }
    }
    if let Some(parent) = next {
        let coefficients = directions.map(|n| Spatial::new(moment.cross(n), total * n));
        for run in model.path_dof_runs(parent) {
            data.axis_components.add_dots(run.clone(), &coefficients, &mut rows);
        }
    }
    for (row, n) in rows.iter_mut().zip(directions) {
        for (k, &(body, x, scale)) in points.iter().enumerate() {
            if on_path & (1 << k) == 0 {
                add_point_row(model, data, body, x, n, scale, row);
            }
        }
    }
}

fn write_spatial(v: &Spatial, mut out: MatMut<'_, f64>, column: usize) {
    let values = [v.angular.x, v.angular.y, v.angular.z, v.linear.x, v.linear.y, v.linear.z];
    for (r, value) in values.into_iter().enumerate() {
        out[(r, column)] = value;
    }
}
