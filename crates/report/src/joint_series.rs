//! Per-joint values over the frames of a run, built from CSV rows that come frame by frame
//! (`forces.csv`, `internal.csv`): K frames × joints matrices, frame-major.

use hagfish_anatomy::MAX_BODY_COUNT;

use crate::csv::Record;
use crate::error::ReportError;
use crate::frame_selection::FrameSelection;

/// K matrices of frames × joints, frame-major (`values[k][f * joints + j]`), with the time
/// of each frame, for the frames a [`FrameSelection`] keeps. `joints` is one more than the
/// largest joint seen; an entry no row gave is 0.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointSeries<const K: usize> {
    /// The frames kept.
    selection: FrameSelection,
    /// Frames seen, kept or not.
    frames_seen: usize,
    /// Simulation time of each kept frame (s).
    pub(crate) times: Vec<f64>,
    /// Joints per frame (0 = head).
    pub(crate) joints: usize,
    /// One matrix per component.
    pub(crate) values: [Vec<f64>; K],
}

impl<const K: usize> JointSeries<K> {
    /// No frame yet; `selection` says which frames to keep.
    pub(crate) fn new(selection: FrameSelection) -> Self {
        let values = [(); K].map(|()| Vec::new());
        Self { selection, frames_seen: 0, times: Vec::new(), joints: 0, values }
    }

    /// Sets component `k` of joint `joint` in frame `frame` (at `time` s) to `value`. The
    /// frame must be the current one or the next (frames numbered from 0 without gaps),
    /// and the joint one that a body can have (below [`MAX_BODY_COUNT`]: a corrupt index must
    /// not size the matrices); otherwise the error names `record`'s field `frame_column` or
    /// `joint_column`.
    pub(crate) fn set(
        &mut self,
        record: &Record<'_>,
        [frame_column, joint_column]: [usize; 2],
        (frame, time): (usize, f64),
        (joint, k): (usize, usize),
        value: f64,
    ) -> Result<(), ReportError> {
        if joint >= MAX_BODY_COUNT {
            let what = format!("is beyond the joints a body can have ({MAX_BODY_COUNT})");
            return Err(record.error(joint_column, &what));
        }
        let kept = self.selection.keeps(frame);
        if frame == self.frames_seen {
            self.frames_seen += 1;
            if kept {
                self.times.push(time);
                let len = self.times.len() * self.joints;
                self.values.iter_mut().for_each(|v| v.resize(len, 0.0));
            }
        } else if frame + 1 != self.frames_seen {
            return Err(record.error(frame_column, "is not the current or the next frame"));
        }
        if !kept {
            return Ok(());
        }
        if joint >= self.joints {
            self.widen(joint + 1);
        }
        let row = self.times.len() - 1;
        self.values[k][row * self.joints + joint] = value;
        Ok(())
    }

    /// Re-lays the matrices out with `joints` columns, the new entries 0. Within the first
    /// frame (where the joints are first seen, one by one) this is a resize.
    fn widen(&mut self, joints: usize) {
        let (frames, old) = (self.times.len(), self.joints);
        for values in &mut self.values {
            if frames <= 1 {
                values.resize(frames * joints, 0.0);
                continue;
            }
            let mut wider = vec![0.0; frames * joints];
            for (row, old_row) in wider.chunks_mut(joints).zip(values.chunks(old.max(1))) {
                row[..old].copy_from_slice(&old_row[..old]);
            }
            *values = wider;
        }
        self.joints = joints;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csv::CsvFile;

    /// The series of a `frame,time_s,joint,k,value` file.
    fn read(text: &str) -> Result<JointSeries<2>, ReportError> {
        read_selected(text, FrameSelection::all())
    }

    fn read_selected(text: &str, selection: FrameSelection) -> Result<JointSeries<2>, ReportError> {
        let path = crate::test_files::write("series.csv", text);
        let file = CsvFile::open(&path)?;
        let mut series = JointSeries::new(selection);
        file.for_each_record(|r| {
            let at = (r.index(0)?, r.number(1)?);
            series.set(r, [0, 2], at, (r.index(2)?, r.index(3)?), r.number(4)?)
        })?;
        Ok(series)
    }

    #[test]
    fn rows_fill_frames_by_joint_and_component_and_absent_entries_are_zero() {
        let series =
            read("f,t,j,k,v\n0,0,0,0,1\n0,0,1,1,2\n1,0.5,1,0,3\n2,1,0,1,4\n").expect("reads");
        assert_eq!(series.times, [0.0, 0.5, 1.0]);
        assert_eq!(series.joints, 2);
        assert_eq!(series.values[0], [1.0, 0.0, 0.0, 3.0, 0.0, 0.0]);
        assert_eq!(series.values[1], [0.0, 2.0, 0.0, 0.0, 4.0, 0.0]);
    }

    #[test]
    fn a_joint_first_seen_in_a_later_frame_widens_every_frame() {
        let series =
            read("f,t,j,k,v\n0,0,0,0,1\n1,1,0,0,2\n1,1,2,1,3\n2,2,1,0,4\n").expect("reads");
        assert_eq!(series.joints, 3);
        assert_eq!(series.values[0], [1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 4.0, 0.0]);
        assert_eq!(series.values[1], [0.0, 0.0, 0.0, 0.0, 0.0, 3.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn only_the_selected_frames_are_kept_and_every_frame_is_checked() {
        let text = "f,t,j,k,v\n0,0,0,0,1\n1,1,0,0,2\n2,2,1,1,3\n3,3,0,0,4\n4,4,0,0,5\n";
        let series =
            read_selected(text, FrameSelection { stride: 2, last: Some(4) }).expect("reads");
        assert_eq!((series.times.clone(), series.joints), (vec![0.0, 2.0, 4.0], 2));
        assert_eq!(series.values[0], [1.0, 0.0, 0.0, 0.0, 5.0, 0.0]);
        assert_eq!(series.values[1], [0.0, 0.0, 0.0, 3.0, 0.0, 0.0]);
        let skipped = "f,t,j,k,v\n0,0,0,0,1\n1,1,0,0,2\n3,3,0,0,4\n";
        let error = read_selected(skipped, FrameSelection { stride: 2, last: Some(3) })
            .expect_err("frame 2 is missing, though not kept");
        assert!(error.to_string().contains("series.csv:4:"), "{error}");
    }

    #[test]
    fn a_frame_out_of_order_is_an_error_at_its_line() {
        let error = read("f,t,j,k,v\n0,0,0,0,1\n2,1,0,0,2\n").expect_err("frame 1 skipped");
        assert!(error.to_string().contains("series.csv:3:"), "{error}");
        let error = read("f,t,j,k,v\n0,0,0,0,1\n1,1,0,0,2\n0,0,1,0,3\n").expect_err("back");
        assert!(error.to_string().contains("series.csv:4:"), "{error}");
        let error = read("f,t,j,k,v\n0,0,99999999999,0,1\n").expect_err("a corrupt joint");
        assert!(error.to_string().contains("series.csv:2: field 3"), "{error}");
    }
}
