//! `hagfish knot FILE`: reads a `centreline.csv` (`frame,time_s,body,x_cm,y_cm,z_cm`, as
//! `hagfish run` writes it) a line at a time and prints the knot type of every frame as it
//! completes. A malformed line is an error at its `file:line:column`.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};

use glam::DVec3;
use hagfish_knots::{KnotAnalyser, KnotOptions};

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
/// file is read a line at a time and each frame printed once it is complete, so a run of any
/// length needs one frame in memory; a malformed line stops it there with its error.
pub fn run(args: &KnotArgs, out: &mut impl Write) -> Result<(), CliError> {
    let file = std::fs::File::open(&args.file).map_err(|e| CliError::RunDirectory {
        path: args.file.clone(),
        reason: format!("cannot read the file: {e}"),
    })?;
    let mut frames = Frames::new(BufReader::new(file), &args.file)?;
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

/// The frames of a centreline CSV, in file order, read a line at a time; rows of one frame
/// must be consecutive.
struct Frames<'a, R> {
    lines: std::iter::Enumerate<std::io::Lines<R>>,
    path: &'a Path,
    /// The header's column names and the places of [`COLUMNS`] among them.
    names: Vec<String>,
    index: [usize; 5],
    /// The frame being read (complete once a row of the next one, or the end, is read).
    current: Option<FramePoints>,
}

impl<'a, R: BufRead> Frames<'a, R> {
    /// Reads the header of `reader` (the file `path`).
    fn new(reader: R, path: &'a Path) -> Result<Self, CliError> {
        let mut lines = reader.lines().enumerate();
        let header = match lines.next() {
            Some((_, line)) => line.map_err(|e| read_error(path, &e))?,
            None => {
                return Err(csv_error(
                    path,
                    1,
                    1,
                    format!("empty file: expected a header with {}", COLUMNS.join(",")),
                ));
            }
        };
        let names: Vec<String> = header.split(',').map(|n| n.trim().to_string()).collect();
        let mut index = [0usize; 5];
        for (slot, wanted) in index.iter_mut().zip(COLUMNS) {
            *slot = names.iter().position(|n| n == wanted).ok_or_else(|| {
                let expected = COLUMNS.join(",");
                csv_error(
                    path,
                    1,
                    1,
                    format!("header has no column `{wanted}`: expected {expected}"),
                )
            })?;
        }
        Ok(Self { lines, path, names, index, current: None })
    }

    /// The next complete frame, or `None` at the end of the file.
    fn next_frame(&mut self) -> Result<Option<FramePoints>, CliError> {
        while let Some((i, line)) = self.lines.next() {
            let line = line.map_err(|e| read_error(self.path, &e))?;
            if line.trim().is_empty() {
                continue;
            }
            if let Some(done) = self.add_row(i + 1, &line)? {
                return Ok(Some(done));
            }
        }
        Ok(self.current.take())
    }

    /// Adds the row at line `number`; returns the frame it completes, if it starts another.
    fn add_row(&mut self, number: usize, line: &str) -> Result<Option<FramePoints>, CliError> {
        let (path, index) = (self.path, self.index);
        let fields: Vec<&str> = line.split(',').collect();
        let width = self.names.len();
        if fields.len() != width {
            return Err(csv_error(
                path,
                number,
                line.chars().count() + 1,
                format!("{} fields, expected {width} as in the header", fields.len()),
            ));
        }
        let column =
            |k: usize| 1 + fields[..k].iter().map(|f| f.chars().count() + 1).sum::<usize>();
        let number_at = |k: usize| -> Result<f64, CliError> {
            let field = fields[k].trim();
            field.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                let message =
                    format!("`{}` = \"{field}\": expected a finite number", self.names[k]);
                csv_error(path, number, column(k), message)
            })
        };
        let frame = fields[index[0]].trim().parse::<u64>().map_err(|_| {
            let message =
                format!("frame = \"{}\": expected a whole number", fields[index[0]].trim());
            csv_error(path, number, column(index[0]), message)
        })?;
        let point = DVec3::new(number_at(index[2])?, number_at(index[3])?, number_at(index[4])?);
        match &mut self.current {
            Some(last) if last.frame == frame => {
                last.points.push(point);
                Ok(None)
            }
            Some(last) if frame < last.frame => Err(csv_error(
                path,
                number,
                column(index[0]),
                format!(
                    "frame {frame} after frame {}: expected the rows of a frame together, frames increasing",
                    last.frame
                ),
            )),
            _ => {
                let next = FramePoints { frame, time: number_at(index[1])?, points: vec![point] };
                Ok(self.current.replace(next))
            }
        }
    }
}

/// A malformed line of `path`, at `line:column`.
fn csv_error(path: &Path, line: usize, column: usize, message: String) -> CliError {
    CliError::Csv { path: path.to_path_buf(), line, column, message }
}

/// A read failure of `path`.
fn read_error(path: &Path, e: &std::io::Error) -> CliError {
    CliError::RunDirectory {
        path: path.to_path_buf(),
        reason: format!("cannot read the file: {e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every frame of `text`, read as `hagfish knot` reads a file.
    fn parse(text: &str, path: &Path) -> Result<Vec<FramePoints>, CliError> {
        let mut frames = Frames::new(text.as_bytes(), path)?;
        let mut all = Vec::new();
        while let Some(frame) = frames.next_frame()? {
            all.push(frame);
        }
        Ok(all)
    }

    fn message(text: &str) -> String {
        match parse(text, Path::new("c.csv")) {
            Ok(_) => String::from("parsed"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn frames_are_grouped_and_errors_are_positioned() {
        let good =
            "frame,time_s,body,x_cm,y_cm,z_cm\n0,0.0,0,1,2,3\n0,0.0,1,2,2,3\n1,0.1,0,1,2,4\n";
        let frames = parse(good, Path::new("c.csv")).expect("parses");
        assert_eq!(frames.len(), 2);
        assert_eq!(frames[0].points.len(), 2);
        assert_eq!(frames[1].points[0], DVec3::new(1.0, 2.0, 4.0));
        let header = "frame,time_s,body,x_cm,y_cm,z_cm\n";
        assert_eq!(
            message(&format!("{header}0,0.0,0,1,x,3\n")),
            "c.csv:2:11: `y_cm` = \"x\": expected a finite number"
        );
        assert_eq!(
            message(&format!("{header}0,0.0,0,1,2\n")),
            "c.csv:2:12: 5 fields, expected 6 as in the header"
        );
        assert!(
            message(&format!("{header}1,0.0,0,1,2,3\n0,0.0,0,1,2,3\n"))
                .starts_with("c.csv:3:1: frame 0 after frame 1")
        );
        assert!(message("frame,x_cm\n").starts_with("c.csv:1:1: header has no column `time_s`"));
        assert!(message("").starts_with("c.csv:1:1: empty file"));
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
