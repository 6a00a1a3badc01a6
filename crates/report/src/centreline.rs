//! `centreline.csv`: the body centres of every recorded frame.

use std::ops::ControlFlow;
use std::path::Path;

use crate::csv::CsvFile;
use crate::error::ReportError;
use crate::frame_selection::FrameSelection;

/// Body centres per frame (cm), frame-major: frame f, body b is `points[f * bodies + b]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Centreline {
    /// Simulation time of each frame (s).
    pub times: Vec<f64>,
    /// Bodies per frame (0 = head).
    pub bodies: usize,
    /// Body centres (cm).
    pub points: Vec<[f64; 3]>,
}

impl Centreline {
    /// Reads `centreline.csv`. Frames must be numbered 0, 1, … with bodies 0, 1, … in order;
    /// a last frame with fewer bodies than the others (a run stopped while writing it) is
    /// dropped.
    pub fn read(path: &Path) -> Result<Self, ReportError> {
        Self::read_selected(path, FrameSelection::all())
    }

    /// [`Centreline::read`] keeping only the frames `selection` keeps (every frame is
    /// checked all the same).
    pub fn read_selected(path: &Path, selection: FrameSelection) -> Result<Self, ReportError> {
        let file = CsvFile::open(path)?;
        let [frame, time, body, x, y, z] =
            ["frame", "time_s", "body", "x_cm", "y_cm", "z_cm"].map(|c| file.column(c));
        let (frame, time, body, x, y, z) = (frame?, time?, body?, x?, y?, z?);
        let mut times = Vec::new();
        let mut points = Vec::new();
        let mut bodies = None;
        // The frame being read: its index, its bodies so far, whether it is kept, and its
        // centres if it is.
        let (mut current_frame, mut current_bodies, mut kept) = (None, 0, false);
        let mut current = Vec::new();
        file.for_each_record(|record| {
            let f = record.index(frame)?;
            if current_frame != Some(f) {
                if let Some(previous) = current_frame {
                    let count = *bodies.get_or_insert(current_bodies);
                    if current_bodies != count {
                        return Err(record.error(
                            frame,
                            &format!(
                                "starts a frame after one of {current_bodies} bodies, not {count}"
                            ),
                        ));
                    }
                    points.append(&mut current);
                    if f != previous + 1 {
                        let next = previous + 1;
                        return Err(record.error(frame, &format!("is not the next frame, {next}")));
                    }
                } else if f != 0 {
                    return Err(record.error(frame, "is not the next frame, 0"));
                }
                kept = selection.keeps(f);
                if kept {
                    times.push(record.number(time)?);
                }
                (current_frame, current_bodies) = (Some(f), 0);
            }
            if record.index(body)? != current_bodies {
                let what = format!("is not the next body, {current_bodies}");
                return Err(record.error(body, &what));
            }
            current_bodies += 1;
            if kept {
                current.push([record.number(x)?, record.number(y)?, record.number(z)?]);
            }
            Ok(())
        })?;
        let count = *bodies.get_or_insert(current_bodies);
        if current_bodies == count {
            points.append(&mut current);
        } else if kept {
            times.pop();
        }
        if times.is_empty() || count < 2 {
            return Err(ReportError::Invalid {
                path: path.to_path_buf(),
                what: "needs at least one frame of at least 2 bodies".into(),
            });
        }
        Ok(Self { times, bodies: count, points })
    }

    /// The bodies of the first frame of `centreline.csv` (read up to the second frame).
    pub fn first_frame_bodies(path: &Path) -> Result<usize, ReportError> {
        let file = CsvFile::open(path)?;
        let frame = file.column("frame")?;
        let mut bodies = 0;
        file.scan(|record| {
            Ok(if record.index(frame)? == 0 {
                bodies += 1;
                ControlFlow::Continue(())
            } else {
                ControlFlow::Break(())
            })
        })?;
        Ok(bodies)
    }

    /// Number of frames.
    pub fn frames(&self) -> usize {
        self.times.len()
    }

    /// The body centres of frame `f`.
    pub fn frame(&self, f: usize) -> &[[f64; 3]] {
        &self.points[f * self.bodies..(f + 1) * self.bodies]
    }

    /// Smallest and largest coordinate per axis over all frames.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let mut low = [f64::INFINITY; 3];
        let mut high = [f64::NEG_INFINITY; 3];
        for p in &self.points {
            for a in 0..3 {
                low[a] = low[a].min(p[a]);
                high[a] = high[a].max(p[a]);
            }
        }
        (low, high)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(name: &str, text: &str) -> Result<Centreline, ReportError> {
        Centreline::read(&crate::test_files::write(name, text))
    }

    const HEADER: &str = "frame,time_s,body,x_cm,y_cm,z_cm\n";

    #[test]
    fn reads_frames_and_drops_a_truncated_last_one() {
        let text = format!(
            "{HEADER}0,0,0,0,0,0\n0,0,1,3,4,0\n1,0.1,0,1,0,0\n1,0.1,1,2,0,-1\n2,0.2,0,1,1,1\n"
        );
        let c = read("ok.csv", &text).expect("reads");
        assert_eq!((c.frames(), c.bodies), (2, 2));
        assert_eq!(c.frame(1), &[[1.0, 0.0, 0.0], [2.0, 0.0, -1.0]]);
        assert_eq!(c.bounds(), ([0.0, 0.0, -1.0], [3.0, 4.0, 0.0]));
    }

    #[test]
    fn a_skipped_body_or_frame_is_an_error_at_its_line() {
        let skipped_body = format!("{HEADER}0,0,0,0,0,0\n0,0,2,3,4,0\n");
        let e = read("body.csv", &skipped_body).expect_err("skipped body");
        assert!(e.to_string().contains("body.csv:3:"), "{e}");
        let skipped_frame = format!("{HEADER}0,0,0,0,0,0\n0,0,1,3,4,0\n2,0,0,0,0,0\n");
        let e = read("frame.csv", &skipped_frame).expect_err("skipped frame");
        assert!(e.to_string().contains("frame.csv:4:"), "{e}");
        assert!(read("empty.csv", HEADER).is_err());
    }
}
