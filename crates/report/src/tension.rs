//! `internal.csv`: the axial tension N (dyn) each joint transmits, per frame (the other load
//! columns are for the user; the report plots the tension).

use std::path::Path;

use crate::csv::CsvFile;
use crate::error::ReportError;
use crate::frame_selection::FrameSelection;
use crate::joint_series::JointSeries;

/// The `tension_dyn` column of `internal.csv` as a frames × joints matrix, frame-major
/// (`values[f * joints + j]`), and at the head (joint 0) on every frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Tension {
    /// Simulation time of each frame of `values` (s).
    pub times: Vec<f64>,
    /// Joints per frame (0 = head).
    pub joints: usize,
    /// Tension per frame and joint (dyn).
    pub values: Vec<f64>,
    /// Simulation time of every frame of the file (s): `times` unless frames were left out
    /// ([`Tension::read_selected`]).
    pub head_times: Vec<f64>,
    /// The tension at joint 0 (the head, where the body pulls on the wall) at `head_times`
    /// (dyn; 0 in a frame without a row for joint 0).
    pub head: Vec<f64>,
}

impl Tension {
    /// Reads `internal.csv`; frames must be numbered from 0 without gaps and list every joint.
    pub fn read(path: &Path) -> Result<Self, ReportError> {
        Self::read_selected(path, FrameSelection::all())
    }

    /// [`Tension::read`] keeping in `values` only the frames `selection` keeps (every frame
    /// is checked all the same, and the tension at the head is kept on every frame: the
    /// report's summary gives its final value, maximum and mean).
    pub fn read_selected(path: &Path, selection: FrameSelection) -> Result<Self, ReportError> {
        let file = CsvFile::open(path)?;
        let [frame, time, joint, tension] =
            ["frame", "time_s", "joint", "tension_dyn"].map(|c| file.column(c));
        let (frame, time, joint, tension) = (frame?, time?, joint?, tension?);
        let mut series = JointSeries::new(selection);
        let (mut head_times, mut head) = (Vec::new(), Vec::new());
        file.for_each_record(|record| {
            let (at, j, value) = (
                (record.index(frame)?, record.number(time)?),
                record.index(joint)?,
                record.number(tension)?,
            );
            series.set(record, [frame, joint], at, (j, 0), value)?;
            if at.0 == head.len() {
                head_times.push(at.1);
                head.push(0.0);
            }
            if j == 0 {
                *head.last_mut().expect("a frame was started above") = value;
            }
            Ok(())
        })?;
        let JointSeries { times, joints, values: [values], .. } = series;
        Ok(Self { times, joints, values, head_times, head })
    }

    /// The tension at joint 0 (the head, where the body pulls on the wall) per frame, at
    /// `head_times` (dyn).
    pub fn at_head(&self) -> Vec<f64> {
        self.head.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_tension_by_frame_and_joint() {
        let text = "frame,time_s,joint,s_cm,tension_dyn,shear_y_dyn,shear_z_dyn,twist_dyn_cm,\
            bend_y_dyn_cm,bend_z_dyn_cm\n\
            0,0,0,0,1.5,0,0,0,0,0\n0,0,1,1,2.5,0,0,0,0,0\n\
            1,0.1,0,0,-3,0,0,0,0,0\n1,0.1,1,1,4,0,0,0,0,0\n";
        let path = crate::test_files::write("internal.csv", text);
        let t = Tension::read(&path).expect("reads");
        assert_eq!((t.times.len(), t.joints), (2, 2));
        assert_eq!(t.values, vec![1.5, 2.5, -3.0, 4.0]);
        assert_eq!(t.at_head(), vec![1.5, -3.0]);
    }
}
