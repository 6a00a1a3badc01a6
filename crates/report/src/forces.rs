//! `forces.csv`: the thigmotaxic force field (group `thigmo`) per frame, joint and axis.

use std::path::Path;

use crate::csv::CsvFile;
use crate::error::ReportError;
use crate::frame_selection::FrameSelection;
use crate::joint_series::JointSeries;

/// The axes of `forces.csv`, in the order of [`ThigmoForces::values`].
pub const AXES: [&str; 3] = ["X", "Y", "Z"];

/// The `thigmo` group of `forces.csv` (dyn·cm): per axis, a frames × joints matrix,
/// frame-major (`values[a][f * joints + j]`); a DOF absent from a frame is 0.
#[derive(Clone, Debug, PartialEq)]
pub struct ThigmoForces {
    /// Simulation time of each frame (s).
    pub times: Vec<f64>,
    /// Joints per frame (0 = head).
    pub joints: usize,
    /// One matrix per axis of [`AXES`].
    pub values: [Vec<f64>; 3],
}

impl ThigmoForces {
    /// Reads the `thigmo` rows of `forces.csv`; frames must be numbered from 0 without gaps.
    pub fn read(path: &Path) -> Result<Self, ReportError> {
        Self::read_selected(path, FrameSelection::all())
    }

    /// [`ThigmoForces::read`] keeping only the frames `selection` keeps (every frame is
    /// checked all the same).
    pub fn read_selected(path: &Path, selection: FrameSelection) -> Result<Self, ReportError> {
        let file = CsvFile::open(path)?;
        let [frame, time, joint, axis, group, value] =
            ["frame", "time_s", "joint", "axis", "group", "value_dyn_cm"].map(|c| file.column(c));
        let (frame, time, joint, axis, group, value) =
            (frame?, time?, joint?, axis?, group?, value?);
        let mut series = JointSeries::new(selection);
        file.for_each_record(|record| {
            if record.text(group) != "thigmo" {
                return Ok(());
            }
            let a = AXES
                .iter()
                .position(|name| *name == record.text(axis))
                .ok_or_else(|| record.error(axis, "is not X, Y or Z"))?;
            let at = (record.index(frame)?, record.number(time)?);
            series.set(record, [frame, joint], at, (record.index(joint)?, a), record.number(value)?)
        })?;
        let JointSeries { times, joints, values, .. } = series;
        Ok(Self { times, joints, values })
    }

    /// Number of frames.
    pub fn frames(&self) -> usize {
        self.times.len()
    }

    /// The mean |f| over the DOFs of every joint and axis in `frames` (indices past the last
    /// frame are left out), `None` for no frame: a phase's mean force (dyn·cm).
    pub fn mean_abs(&self, frames: &[usize]) -> Option<f64> {
        let frames: Vec<usize> = frames.iter().copied().filter(|&f| f < self.frames()).collect();
        let count = frames.len() * AXES.len() * self.joints;
        let sum: f64 = frames
            .iter()
            .flat_map(|&f| {
                self.values.iter().flat_map(move |a| &a[f * self.joints..][..self.joints])
            })
            .map(|x| x.abs())
            .sum();
        (count > 0).then(|| sum / count as f64)
    }

    /// The largest magnitude on axis `a` (0 if there is none).
    pub fn max_abs(&self, a: usize) -> f64 {
        self.values[a].iter().fold(0.0, |m, v| m.max(v.abs()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_only_thigmo_rows_by_frame_joint_and_axis() {
        let text = "frame,time_s,joint,axis,group,value_dyn_cm\n\
            0,0,0,X,limit,9\n0,0,0,X,thigmo,1\n0,0,1,Z,thigmo,-2\n\
            1,0.1,0,Y,thigmo,3e1\n1,0.1,1,X,contact,7\n";
        let path = crate::test_files::write("forces.csv", text);
        let f = ThigmoForces::read(&path).expect("reads");
        assert_eq!((f.frames(), f.joints), (2, 2));
        assert_eq!(f.values[0], vec![1.0, 0.0, 0.0, 0.0]);
        assert_eq!(f.values[1], vec![0.0, 0.0, 30.0, 0.0]);
        assert_eq!(f.values[2], vec![0.0, -2.0, 0.0, 0.0]);
        assert_eq!((f.max_abs(0), f.max_abs(1), f.max_abs(2)), (1.0, 30.0, 2.0));
        // Means over 3 axes × 2 joints of the frames asked for; frame 5 does not exist.
        assert_eq!(f.mean_abs(&[0]), Some(3.0 / 6.0));
        assert_eq!(f.mean_abs(&[0, 1, 5]), Some(33.0 / 12.0));
        assert_eq!(f.mean_abs(&[5]), None);
        std::fs::write(&path, "frame,time_s,joint,axis,group,value_dyn_cm\n0,0,0,W,thigmo,1\n")
            .expect("write");
        let e = ThigmoForces::read(&path).expect_err("bad axis");
        assert!(e.to_string().contains("forces.csv:2:"), "{e}");
    }
}
