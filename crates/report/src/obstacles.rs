//! The run's obstacles (the `obstacles` of its `scenario.ron`) as wireframes: a few circles
//! and lines per obstacle that show its shape in the animation, the report's 3-D view,
//! ParaView (`vtk/`) and `run.glb`. Each is one [`ObstacleTrack`], its wireframe posed at
//! offset zero and its [`Pose`] at each frame (its offset on its path and its turn); planes
//! and infinite cylinders are cut to the run's surroundings.

use std::f64::consts::TAU;
use std::path::Path;

use glam::{DQuat, DVec3};
use hagfish_anatomy::DataFile;
#[cfg(test)]
use hagfish_geometry::Spin;
use hagfish_geometry::{MovingObstacle, Obstacle, ObstaclePath};
use hagfish_scenario::Scenario;

use crate::run_dir::RunDir;

/// Segments of each circle.
const SEGMENTS: usize = 48;
/// Grid lines each way across a plane, and lines along a cylinder.
const LINES: usize = 8;

/// A wireframe: polylines of world points (cm).
pub type Wireframe = Vec<Vec<[f64; 3]>>;

/// The obstacles of the run whose scenario file is `scenario`: none when it does not exist,
/// cannot be read or names an obstacle that is not one (`hagfish run` refused such a run).
pub fn of_run(scenario: &Path) -> Vec<MovingObstacle> {
    let Ok(file) = DataFile::<Scenario>::read(scenario) else { return Vec::new() };
    file.value.obstacles.iter().filter_map(|spec| spec.to_obstacle().ok()).collect()
}

/// Where an obstacle's wireframe is at one frame: x ↦ R x + t, a rotation R and a
/// translation t (cm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// R.
    pub rotation: DQuat,
    /// t (cm).
    pub translation: DVec3,
}

impl Pose {
    /// The pose of `obstacle` at time `t` (s): its offset on its path and its turn ω t (if it
    /// turns) about its reference point p, so x ↦ R(x − p) + p + offset.
    pub fn of(obstacle: &MovingObstacle, t: f64) -> Self {
        let rotation = obstacle.spin.map_or(DQuat::IDENTITY, |spin| spin.rotation(t));
        let p = obstacle.shape.reference_point();
        Pose { rotation, translation: obstacle.path.offset(t) + p - rotation * p }
    }

    /// R x + t.
    pub fn apply(&self, x: [f64; 3]) -> [f64; 3] {
        (self.rotation * DVec3::from_array(x) + self.translation).to_array()
    }
}

/// An obstacle of a run: its wireframe at offset zero and its pose at each frame (empty when
/// it neither moves nor turns).
#[derive(Clone, Debug, PartialEq)]
pub struct ObstacleTrack {
    /// The wireframe, posed at offset zero (cm).
    pub lines: Wireframe,
    /// The pose at each frame, or none.
    pub poses: Vec<Pose>,
}

/// The wireframe of every track where it is at frame `f`.
pub fn at_frame(tracks: &[ObstacleTrack], f: usize) -> Wireframe {
    let mut wireframe = Wireframe::new();
    for track in tracks {
        let lines = track.lines.iter();
        match track.poses.get(f) {
            Some(pose) => {
                wireframe.extend(lines.map(|l| l.iter().map(|&p| pose.apply(p)).collect()))
            }
            None => wireframe.extend(lines.cloned()),
        }
    }
    wireframe
}

/// The obstacles of `run`: each one's wireframe at offset zero around the region the body
/// sweeps, and its pose at each frame when it moves or turns.
pub fn tracks(run: &RunDir) -> Vec<ObstacleTrack> {
    let (centre, extent) = surroundings(run);
    let still = ObstaclePath::default();
    let track = |o: &MovingObstacle| ObstacleTrack {
        lines: wireframe(&o.shape, centre, extent),
        poses: match o.path == still && o.spin.is_none() {
            true => Vec::new(),
            false => run.centreline.times.iter().map(|&t| Pose::of(o, t)).collect(),
        },
    };
    run.obstacles.iter().map(track).collect()
}

/// The centre and half-size (cm) of the region the body of `run` sweeps: its centreline's
/// bounding box grown by the largest radius.
fn surroundings(run: &RunDir) -> (DVec3, f64) {
    let (low, high) = run.centreline.bounds();
    let margin = run.radii.values.iter().fold(0.0, |m: f64, r| m.max(*r));
    let centre = DVec3::from_array([0, 1, 2].map(|a| 0.5 * (low[a] + high[a])));
    let extent = (0..3).map(|a| 0.5 * (high[a] - low[a]) + margin).fold(1e-6, f64::max);
    (centre, extent)
}

/// The wireframe of `obstacle` around the region of centre `centre` and half-size `extent`
/// (cm): a plane as a square grid of side 2·`extent` about the centre's foot on it, a sphere
/// as three great circles, a cylinder as rings at its ends and middle and lines along it
/// (an infinite one 2·`extent` long about the centre's foot on its axis).
pub fn wireframe(obstacle: &Obstacle, centre: DVec3, extent: f64) -> Wireframe {
    match *obstacle {
        Obstacle::Plane { point, normal } => {
            let foot = centre - normal * normal.dot(centre - point);
            let (u, v) = normal.any_orthonormal_pair();
            let line = |k: usize, along: DVec3, across: DVec3| {
                let offset = extent * (2.0 * k as f64 / (LINES - 1) as f64 - 1.0);
                let a = foot + across * offset;
                vec![to_array(a - along * extent), to_array(a + along * extent)]
            };
            (0..LINES).flat_map(|k| [line(k, u, v), line(k, v, u)]).collect()
        }
        Obstacle::Sphere { centre: c, radius } => {
            [(DVec3::X, DVec3::Y), (DVec3::Y, DVec3::Z), (DVec3::Z, DVec3::X)]
                .map(|(u, v)| circle(c, u * radius, v * radius))
                .to_vec()
        }
        Obstacle::Cylinder { point, axis, radius, half_length } => {
            let half = half_length.unwrap_or(extent);
            let middle = match half_length {
                Some(_) => point,
                None => point + axis * axis.dot(centre - point),
            };
            let (u, v) = axis.any_orthonormal_pair();
            let mut lines: Wireframe = [-1.0, 0.0, 1.0]
                .map(|s| circle(middle + axis * (s * half), u * radius, v * radius))
                .to_vec();
            for k in 0..LINES {
                let angle = TAU * k as f64 / LINES as f64;
                let rim = (u * angle.cos() + v * angle.sin()) * radius;
                let ends = [middle - axis * half + rim, middle + axis * half + rim];
                lines.push(ends.map(to_array).to_vec());
            }
            lines
        }
    }
}

/// The circle c + u cos φ + v sin φ, closed.
fn circle(c: DVec3, u: DVec3, v: DVec3) -> Vec<[f64; 3]> {
    (0..=SEGMENTS)
        .map(|k| {
            let phi = TAU * k as f64 / SEGMENTS as f64;
            to_array(c + u * phi.cos() + v * phi.sin())
        })
        .collect()
}

fn to_array(p: DVec3) -> [f64; 3] {
    p.to_array()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_wireframe_lies_on_its_obstacle_and_planes_stay_near_the_run() {
        let centre = DVec3::new(1.0, 2.0, 3.0);
        let obstacles = [
            Obstacle::plane(DVec3::new(0.0, -5.0, 0.0), DVec3::Y),
            Obstacle::sphere(DVec3::new(10.0, 0.0, 3.0), 1.5),
            Obstacle::cylinder(DVec3::new(20.0, -3.0, 0.0), DVec3::Z, 2.0, Some(5.0)),
            Obstacle::cylinder(DVec3::ZERO, DVec3::X, 0.5, None),
        ];
        for obstacle in obstacles {
            let obstacle = obstacle.expect("valid");
            let lines = wireframe(&obstacle, centre, 4.0);
            assert!(!lines.is_empty());
            for p in lines.iter().flatten() {
                let p = DVec3::from_array(*p);
                let (distance, _) = obstacle.distance(p);
                assert!(distance.abs() < 1e-9, "{obstacle:?}: {p} is {distance} off");
                assert!((p - centre).length() < 40.0, "{obstacle:?}: {p} far from the run");
            }
        }
    }

    #[test]
    fn a_track_is_drawn_at_its_frames_pose_and_a_still_one_where_it_stands() {
        let line = vec![vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]];
        let still = ObstacleTrack { lines: line.clone(), poses: Vec::new() };
        let shifted = Pose { rotation: DQuat::IDENTITY, translation: DVec3::new(0.0, 2.0, 0.0) };
        let moving = ObstacleTrack { lines: line, poses: vec![shifted; 2] };
        let drawn = at_frame(&[still, moving], 1);
        assert_eq!(
            drawn,
            vec![vec![[0.0; 3], [1.0, 0.0, 0.0]], vec![[0.0, 2.0, 0.0], [1.0, 2.0, 0.0]]]
        );
    }

    #[test]
    fn a_turning_obstacle_turns_about_its_reference_point_and_moves_on_its_path() {
        let roller =
            Obstacle::cylinder(DVec3::new(1.0, 0.0, 0.0), DVec3::Z, 0.5, None).expect("a roller");
        let spin = Spin::new(&roller, DVec3::Z, std::f64::consts::FRAC_PI_2).expect("a spin");
        let path = ObstaclePath::new(vec![(0.0, DVec3::ZERO), (1.0, DVec3::new(0.0, 0.0, 3.0))])
            .expect("a path");
        let turning = MovingObstacle { shape: roller, path, spin: Some(spin) };
        // After 1 s: a quarter turn about the axis through (1, 0, 0), then 3 cm up.
        let pose = Pose::of(&turning, 1.0);
        let moved = DVec3::from_array(pose.apply([1.5, 0.0, 0.0]));
        assert!((moved - DVec3::new(1.0, 0.5, 3.0)).length() < 1e-15, "{moved}");
        let axis_point = DVec3::from_array(pose.apply([1.0, 0.0, 2.0]));
        assert!((axis_point - DVec3::new(1.0, 0.0, 5.0)).length() < 1e-15, "{axis_point}");
    }

    #[test]
    fn the_obstacles_of_a_run_are_read_from_its_scenario() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let form = root.join("data/scenarios/form.ron");
        assert!(of_run(&form).is_empty());
        assert!(of_run(&root.join("no such file.ron")).is_empty());
        let text = std::fs::read_to_string(&form).expect("form.ron");
        let with = text.replacen(
            "Scenario(",
            "Scenario(\n    obstacles: [Sphere(centre: (1.0, 2.0, 3.0), radius: 0.5)],",
            1,
        );
        let dir = std::env::temp_dir().join(format!("hagfish-obstacles-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("scenario.ron");
        std::fs::write(&path, with).expect("write");
        let sphere = Obstacle::sphere(DVec3::new(1.0, 2.0, 3.0), 0.5).expect("valid");
        assert_eq!(of_run(&path), vec![sphere.into()]);
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
