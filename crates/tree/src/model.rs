//! The immutable model: bodies, joints and per-DOF parameters, built and validated by
//! [`ModelBuilder`].
//!
//! Topology: body `i` hangs from joint `i`; joint `i` connects body `i` to its parent body
//! (or to the world for a root). Parents come first (`parent < i`), so a forward loop over
//! bodies visits parents before children and a backward loop visits children first. The
//! DOFs of joint `i` are contiguous, in joint order.

use std::ops::Range;

use glam::DVec3;

use crate::error::TreeError;
use crate::joint::{DofParams, JointKind};
use crate::spatial::Transform;

/// One rigid body. Its frame sits at its centre of mass with principal axes.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Mass (g).
    pub mass: f64,
    /// Principal moments of inertia about the body axes through the centre of mass (g·cm²).
    pub principal_inertia: DVec3,
    /// The body frame in its joint's frame (`E_ji`), constant.
    pub offset: Transform,
    /// Radius used by contact geometry (cm).
    pub radius: f64,
    /// Length along the body's X axis, used by contact geometry (cm).
    pub length: f64,
    /// The compressible outer layer of the contact tube, if any (`radius` is its outside).
    pub skin: Option<Skin>,
}

/// The compressible outer layer of a body's contact tube (docs/physics.md, "Skin"): a contact
/// may compress it, against the pressure of the fluid under it, down to the hard core of
/// radius `radius − thickness`, never deeper.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Skin {
    /// Thickness t of the layer (cm), 0 < t < radius.
    pub thickness: f64,
    /// Pressure p of the fluid under the skin (dyn/cm²), > 0: two tubes crossing with their
    /// skins compressed by δ in all press on a patch of area π√(r_a r_b)·δ, with the force
    /// p·π√(r_a r_b)·δ.
    pub pressure: f64,
}

/// One joint, connecting a body to its parent.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Kind and axes.
    pub kind: JointKind,
    /// Parent body, or `None` for a joint anchored to the world.
    pub parent: Option<usize>,
    /// The joint frame relative to the parent's *joint* frame at `q = 0` (`E⁰_pj`); for a
    /// root, relative to the world.
    pub offset: Transform,
    /// Index of the joint's first DOF in `q`.
    pub dof_start: usize,
}

impl Joint {
    /// The range of this joint's DOFs in `q`.
    pub fn dofs(&self) -> std::ops::Range<usize> {
        self.dof_start..self.dof_start + self.kind.dof_count()
    }
}

/// Everything needed to add one body and its joint to a [`ModelBuilder`].
#[derive(Clone, Debug, PartialEq)]
pub struct BodySpec {
    /// Parent body, or `None` to anchor the joint to the world.
    pub parent: Option<usize>,
    /// Joint kind.
    pub joint: JointKind,
    /// Joint frame relative to the parent's joint frame at `q = 0` (or to the world).
    pub joint_offset: Transform,
    /// Body frame (centre of mass, principal axes) relative to the joint frame.
    pub body_offset: Transform,
    /// Mass (g), > 0.
    pub mass: f64,
    /// Principal moments of inertia (g·cm²), each > 0.
    pub principal_inertia: DVec3,
    /// Contact radius (cm), > 0.
    pub radius: f64,
    /// Length (cm), > 0.
    pub length: f64,
    /// The compressible outer layer of the contact tube, if any (0 < thickness < radius,
    /// pressure > 0).
    pub skin: Option<Skin>,
    /// One entry per DOF of `joint` (extra entries are an error).
    pub dofs: Vec<DofParams>,
}

/// The immutable description of a multibody tree. Build it with [`ModelBuilder`].
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    bodies: Vec<Body>,
    joints: Vec<Joint>,
    dofs: Vec<DofParams>,
    dof_joint: Vec<usize>,
    gravity: DVec3,
    /// [`Model::path_dof_runs`] of every body, concatenated: body `i`'s runs are
    /// `path_runs[path_run_starts[i]..path_run_starts[i + 1]]`.
    path_runs: Vec<Range<usize>>,
    path_run_starts: Vec<usize>,
}

impl Model {
    /// The bodies, in topological order.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The joints; joint `i` carries body `i`.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Per-DOF parameters, indexed like `q`.
    pub fn dofs(&self) -> &[DofParams] {
        &self.dofs
    }

    /// The joint that owns each DOF.
    pub fn dof_joint(&self) -> &[usize] {
        &self.dof_joint
    }

    /// Number of bodies.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Number of reduced coordinates `n = dim q`.
    pub fn dof_count(&self) -> usize {
        self.dofs.len()
    }

    /// Uniform gravitational acceleration (cm/s²); zero for the hagfish (neutral buoyancy).
    pub fn gravity(&self) -> DVec3 {
        self.gravity
    }

    /// Total mass (g).
    pub fn total_mass(&self) -> f64 {
        self.bodies.iter().map(|b| b.mass).sum()
    }

    /// Checks that a vector meant for this model's DOFs has the right length.
    pub fn check_dof_vector(&self, what: &'static str, len: usize) -> Result<(), TreeError> {
        if len == self.dof_count() {
            Ok(())
        } else {
            Err(TreeError::DimensionMismatch { what, got: len, expected: self.dof_count() })
        }
    }

    /// Checks a body index.
    pub fn check_body(&self, what: &'static str, body: usize) -> Result<(), TreeError> {
        if body < self.body_count() {
            Ok(())
        } else {
            Err(TreeError::NoSuchBody { what, body, count: self.body_count() })
        }
    }
}

/// Builds a [`Model`] body by body and validates every quantity.
#[derive(Clone, Debug, Default)]
pub struct ModelBuilder {
    specs: Vec<BodySpec>,
    gravity: DVec3,
}

impl ModelBuilder {
    /// An empty builder with zero gravity.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the gravitational acceleration (cm/s²).
    pub fn gravity(mut self, g: DVec3) -> Self {
        self.gravity = g;
        self
    }

    /// Adds a body and returns its index (checked in [`ModelBuilder::build`]).
    pub fn add_body(&mut self, spec: BodySpec) -> usize {
        self.specs.push(spec);
        self.specs.len() - 1
    }

    /// Validates and builds the model.
    pub fn build(self) -> Result<Model, TreeError> {
        if self.specs.is_empty() {
            return Err(TreeError::Empty);
        }
        let mut model = Model {
            bodies: Vec::with_capacity(self.specs.len()),
            joints: Vec::with_capacity(self.specs.len()),
            dofs: Vec::new(),
            dof_joint: Vec::new(),
            gravity: self.gravity,
            path_runs: Vec::new(),
            path_run_starts: vec![0],
        };
        if !self.gravity.is_finite() {
            return Err(TreeError::InvalidBody {
                body: 0,
                quantity: "gravity",
                value: f64::NAN,
                expected: "finite",
            });
        }
        for (i, spec) in self.specs.into_iter().enumerate() {
            validate_spec(i, &spec)?;
            let dof_start = model.dofs.len();
            model.dofs.extend_from_slice(&spec.dofs);
            model.dof_joint.extend(std::iter::repeat_n(i, spec.dofs.len()));
            model.joints.push(Joint {
                kind: spec.joint,
                parent: spec.parent,
                offset: spec.joint_offset,
                dof_start,
            });
            model.bodies.push(Body {
                mass: spec.mass,
                principal_inertia: spec.principal_inertia,
                offset: spec.body_offset,
                radius: spec.radius,
                length: spec.length,
                skin: spec.skin,
            });
        }
        // A body's runs are its own DOFs followed by its parent's runs (parents come first),
        // the first of those merged into its own when contiguous: O(runs) per body, so a chain
        // of 100 000 bodies builds in milliseconds rather than walking every path.
        for body in 0..model.joints.len() {
            let own = model.joints[body].dofs();
            let parent_runs = match model.joints[body].parent {
                Some(p) => model.path_run_starts[p]..model.path_run_starts[p + 1],
                None => 0..0,
            };
            let mut inherited = parent_runs;
            match inherited.clone().next().map(|k| model.path_runs[k].clone()) {
                Some(first) if own.start == first.end => {
                    inherited.next();
                    model.path_runs.push(first.start..own.end);
                }
                _ => model.path_runs.push(own),
            }
            for k in inherited {
                let run = model.path_runs[k].clone();
                model.path_runs.push(run);
            }
            model.path_run_starts.push(model.path_runs.len());
        }
        Ok(model)
    }
}

fn validate_spec(i: usize, spec: &BodySpec) -> Result<(), TreeError> {
    if let Some(p) = spec.parent
        && p >= i
    {
        return Err(TreeError::BadParent { body: i, parent: p });
    }
    let positive = |quantity: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(TreeError::InvalidBody { body: i, quantity, value, expected: "finite and > 0" })
        }
    };
    positive("mass", spec.mass)?;
    positive("inertia x", spec.principal_inertia.x)?;
    positive("inertia y", spec.principal_inertia.y)?;
    positive("inertia z", spec.principal_inertia.z)?;
    positive("radius", spec.radius)?;
    positive("length", spec.length)?;
    if let Some(skin) = spec.skin {
        positive("skin thickness", skin.thickness)?;
        positive("skin pressure", skin.pressure)?;
        if skin.thickness >= spec.radius {
            return Err(TreeError::InvalidBody {
                body: i,
                quantity: "skin thickness",
                value: skin.thickness,
                expected: "below the radius (the core keeps a radius > 0)",
            });
        }
    }
    for (quantity, t) in [("joint offset", &spec.joint_offset), ("body offset", &spec.body_offset)]
    {
        if !(t.translation.is_finite() && t.rotation.is_finite()) {
            return Err(TreeError::InvalidBody {
                body: i,
                quantity,
                value: f64::NAN,
                expected: "finite",
            });
        }
    }
    if let JointKind::Revolute { axis } = spec.joint
        && (!axis.is_finite() || (axis.length() - 1.0).abs() > 1e-9)
    {
        return Err(TreeError::InvalidBody {
            body: i,
            quantity: "revolute axis length",
            value: axis.length(),
            expected: "a unit vector",
        });
    }
    if spec.dofs.len() != spec.joint.dof_count() {
        return Err(TreeError::DimensionMismatch {
            what: "DOF parameters of a body's joint",
            got: spec.dofs.len(),
            expected: spec.joint.dof_count(),
        });
    }
    for (k, d) in spec.dofs.iter().enumerate() {
        let bad = |quantity, value, expected| TreeError::InvalidDof {
            body: i,
            dof: k,
            quantity,
            value,
            expected,
        };
        if !(d.stiffness.is_finite() && d.stiffness >= 0.0) {
            return Err(bad("stiffness", d.stiffness, "finite and ≥ 0"));
        }
        if !(d.damping.is_finite() && d.damping >= 0.0) {
            return Err(bad("damping", d.damping, "finite and ≥ 0"));
        }
        if !d.rest.is_finite() {
            return Err(bad("rest angle", d.rest, "finite"));
        }
        if d.lower.is_nan() || d.upper.is_nan() || d.lower >= d.upper {
            return Err(bad("lower limit", d.lower, "below the upper limit"));
        }
    }
    Ok(())
}

impl Model {
    /// The joints from `body`'s own joint up to its root, in that order. A body's twist is the
    /// sum of the motions of exactly these joints' DOFs.
    pub fn path_to_root(&self, body: usize) -> PathToRoot<'_> {
        PathToRoot { joints: &self.joints, next: Some(body) }
    }

    /// The DOFs of [`Model::path_to_root`]`(body)` as maximal contiguous ranges, deepest
    /// first: a joint's DOFs join the range of its child when they end where it starts. A
    /// chain gives the single range `0..end`; each branch point starts a new range. Computed
    /// once when the model is built.
    pub fn path_dof_runs(&self, body: usize) -> &[Range<usize>] {
        &self.path_runs[self.path_run_starts[body]..self.path_run_starts[body + 1]]
    }
}

/// Iterator over the joints on the path from a body to its root; see [`Model::path_to_root`].
#[derive(Clone, Debug)]
pub struct PathToRoot<'a> {
    joints: &'a [Joint],
    next: Option<usize>,
}

impl<'a> Iterator for PathToRoot<'a> {
    type Item = &'a Joint;

    fn next(&mut self) -> Option<&'a Joint> {
        let i = self.next?;
        let joint = &self.joints[i];
        self.next = joint.parent;
        Some(joint)
    }
}
