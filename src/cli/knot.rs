//! `hagfish knot FILE`: reads a `centreline.csv` (`frame,time_s,body,x_cm,y_cm,z_cm`, as
//! `hagfish run` writes it) a line at a time and prints the knot type of every frame as it
//! completes, through the report's CSV reader. A malformed line is an error at its
//! `file:line`, naming the column.

use std::io::Write;
use std::path::PathBuf;

use glam::DVec3;
use hagfish_knots::{KnotAnalyser, KnotOptions};
use hagfish_report::{CsvFile, Rows};

use super::CliError;

/// Arguments of `hagfish knot`.
#[derive(Debug, clap::Args)]
pub struct KnotArgs {
    /// A centreline CSV, e.g. out/form/centreline.csv.
    file: PathBuf,
}

/// The columns read, by header name.
const COLUMNS: [&str; 5] = ["frame", "time_s", "x_cm", "y_cm", "z_cm"];

/// One frame's centreline.
struct FramePoints {
    frame: u64,
    time: f64,
    points: Vec<DVec3>,
}

/// Reads the file and prints `frame time_s knot agreement knotted_bodies position_cm` per
/// frame (`-` where the analysis found no knotted stretch, the reason where it failed). The
/// file is read a row at a time and each frame printed once it is complete, so a run of any
/// length needs one frame in memory; a malformed line stops it there with its error.
pub fn run(args: &KnotArgs, out: &mut impl Write) -> Result<(), CliError> {
    let file = CsvFile::open(&args.file)?;
    let mut frames = Frames::new(&file)?;
    let (options, mut analyser) = (KnotOptions::default(), KnotAnalyser::default());
    writeln!(
        out,
        "{:>6}  {:>9}  {:>6}  {:>9}  {:>14}  position_cm",
        "frame", "time_s", "knot", "agreement", "knotted_bodies"
    )?;
    while let Some(f) = frames.next_frame()? {
        match analyser.analyse(&f.points, &options) {
            Ok(k) => writeln!(
                out,
                "{:>6}  {:>9.4}  {:>6}  {:>9.3}  {:>14}  {}",
                f.frame,
                f.time,
                k.knot.to_string(),
                k.agreement,
                k.extent.map_or("-".into(), |(a, b)| format!("{a}-{b}")),
                k.position.map_or("-".into(), |p| format!("{p:.3}")),
            )?,
            Err(e) => writeln!(out, "{:>6}  {:>9.4}  ?  ({e})", f.frame, f.time)?,
        }
    }
    Ok(())
}

/// The frames of a centreline CSV, in file order, read a row at a time by the report's CSV
/// reader; rows of one frame must be consecutive.
struct Frames<'a> {
    rows: Rows<'a>,
    /// The places of [`COLUMNS`] in the header.
    index: [usize; 5],
    /// The frame being read (complete once a row of the next one, or the end, is read).
    current: Option<FramePoints>,
}

impl<'a> Frames<'a> {
    /// The frames of `file`, whose header must have every one of [`COLUMNS`].
    fn new(file: &'a CsvFile) -> Result<Self, CliError> {
        let mut index = [0usize; 5];
        for (slot, wanted) in index.iter_mut().zip(COLUMNS) {
            *slot = file.column(wanted)?;
        }
        Ok(Self { rows: file.rows()?, index, current: None })
    }

    /// The next complete frame, or `None` at the end of the file.
    fn next_frame(&mut self) -> Result<Option<FramePoints>, CliError> {
        let index = self.index;
        while let Some(row) = self.rows.next_record()? {
            let frame = row.index(index[0])? as u64;
            let point =
                DVec3::new(row.number(index[2])?, row.number(index[3])?, row.number(index[4])?);
            match &mut self.current {
                Some(last) if last.frame == frame => last.points.push(point),
                Some(last) if frame < last.frame => {
                    let what = format!(
                        "comes after frame {}: expected the rows of a frame together, frames increasing",
                        last.frame
                    );
                    return Err(row.error(index[0], &what).into());
                }
                _ => {
                    let next =
                        FramePoints { frame, time: row.number(index[1])?, points: vec![point] };
                    if let Some(done) = self.current.replace(next) {
                        return Ok(Some(done));
                    }
                }
            }
        }
        Ok(self.current.take())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every frame of `text`, read as `hagfish knot` reads a file (written to `name`).
    fn parse(text: &str, name: &str) -> Result<Vec<FramePoints>, CliError> {
        let dir = std::env::temp_dir().join(format!("hagfish-knot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temporary folder");
        let path = dir.join(name);
        std::fs::write(&path, text).expect("write");
        let file = CsvFile::open(&path)?;
        let mut frames = Frames::new(&file)?;
        let mut all = Vec::new();
        while let Some(frame) = frames.next_frame()? {
            all.push(frame);
        }
        Ok(all)
    }

    /// The error of reading `text`, from the file name on.
    fn message(text: &str) -> String {
        match parse(text, "c.csv") {
            Ok(_) => String::from("parsed"),
            Err(e) => {
                let e = e.to_string();
                e.find("c.csv").map_or(e.clone(), |at| e[at..].to_owned())
            }
        }
    }

    #[test]
    fn frames_are_grouped_and_errors_are_positioned() {
        let good =
            "frame,time_s,body,x_cm,y_cm,z_cm\n0,0.0,0,1,2,3\n0,0.0,1,2,2,3\n1,0.1,0,1,2,4\n";
        let frames = parse(good, "good.csv").expect("parses");
        assert_eq!(frames.len(), 2);
        assert_eq!(frames[0].points.len(), 2);
        assert_eq!(frames[1].points[0], DVec3::new(1.0, 2.0, 4.0));
        let header = "frame,time_s,body,x_cm,y_cm,z_cm\n";
        assert_eq!(
            message(&format!("{header}0,0.0,0,1,x,3\n")),
            "c.csv:2: field 5 `y_cm` (\"x\") is not a finite number"
        );
        assert_eq!(
            message(&format!("{header}0,0.0,0,1,2\n")),
            "c.csv:2: 5 fields where the header has 6"
        );
        assert!(
            message(&format!("{header}1,0.0,0,1,2,3\n0,0.0,0,1,2,3\n"))
                .starts_with("c.csv:3: field 1 `frame` (\"0\") comes after frame 1")
        );
        assert!(message("frame,x_cm\n").starts_with("c.csv:1: no column \"time_s\""));
        assert!(message("").starts_with("c.csv:1: no header line"));
    }

    #[test]
    fn frames_are_printed_as_they_complete_before_a_later_malformed_line() {
        let path = std::env::temp_dir().join(format!("hagfish-knot-{}.csv", std::process::id()));
        let square = |f: usize, t: f64| {
            (0..4).map(|b| format!("{f},{t},{b},{},{},0\n", b % 2, b / 2)).collect::<String>()
        };
        let rows = format!("{}1,0.1,0,0,0,0\n1,0.1,1,x,0,0\n", square(0, 0.0));
        let text = format!("frame,time_s,body,x_cm,y_cm,z_cm\n{rows}");
        std::fs::write(&path, text).expect("write");
        let mut out = Vec::new();
        let result = run(&KnotArgs { file: path.clone() }, &mut out);
        let _ = std::fs::remove_file(&path);
        let printed = String::from_utf8(out).expect("UTF-8");
        assert_eq!(printed.lines().count(), 2, "the header and frame 0: {printed}");
        assert!(printed.lines().nth(1).is_some_and(|row| row.trim_start().starts_with("0 ")));
        let error = result.expect_err("frame 1 is malformed").to_string();
        assert!(error.contains(":7:") && error.contains("x_cm"), "{error}");
    }
}
