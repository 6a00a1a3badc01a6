//! `hagfish knot FILE`: reads a `centreline.csv` (`frame,time_s,body,x_cm,y_cm,z_cm`, as
//! `hagfish run` writes it) and prints the knot type of every frame. A malformed file is an
//! error at its `file:line:column`.

use std::io::Write;
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
/// frame (`-` where the analysis found no knotted stretch, the reason where it failed).
pub fn run(args: &KnotArgs, out: &mut impl Write) -> Result<(), CliError> {
    let text = std::fs::read_to_string(&args.file).map_err(|e| CliError::RunDirectory {
        path: args.file.clone(),
        reason: format!("cannot read the file: {e}"),
    })?;
    let frames = parse(&text, &args.file)?;
    let (options, mut analyser) = (KnotOptions::default(), KnotAnalyser::default());
    writeln!(
        out,
        "{:>6}  {:>9}  {:>6}  {:>9}  {:>14}  position_cm",
        "frame", "time_s", "knot", "agreement", "knotted_bodies"
    )?;
    for f in &frames {
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

/// The frames of a centreline CSV, in file order; rows of one frame must be consecutive.
fn parse(text: &str, path: &Path) -> Result<Vec<FramePoints>, CliError> {
    let error = |line: usize, column: usize, message: String| CliError::Csv {
        path: path.to_path_buf(),
        line,
        column,
        message,
    };
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let Some((_, header)) = lines.next() else {
        return Err(error(
            1,
            1,
            format!("empty file: expected a header with {}", COLUMNS.join(",")),
        ));
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let mut index = [0usize; 5];
    for (slot, wanted) in index.iter_mut().zip(COLUMNS) {
        *slot = names.iter().position(|n| *n == wanted).ok_or_else(|| {
            error(1, 1, format!("header has no column `{wanted}`: expected {}", COLUMNS.join(",")))
        })?;
    }
    let mut frames: Vec<FramePoints> = Vec::new();
    for (number, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != names.len() {
            return Err(error(
                number,
                line.chars().count() + 1,
                format!("{} fields, expected {} as in the header", fields.len(), names.len()),
            ));
        }
        let column =
            |k: usize| 1 + fields[..k].iter().map(|f| f.chars().count() + 1).sum::<usize>();
        let number_at = |k: usize| -> Result<f64, CliError> {
            let field = fields[k].trim();
            field.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| {
                error(
                    number,
                    column(k),
                    format!("`{}` = \"{field}\": expected a finite number", names[k]),
                )
            })
        };
        let frame = fields[index[0]].trim().parse::<u64>().map_err(|_| {
            error(
                number,
                column(index[0]),
                format!("frame = \"{}\": expected a whole number", fields[index[0]].trim()),
            )
        })?;
        let point = DVec3::new(number_at(index[2])?, number_at(index[3])?, number_at(index[4])?);
        match frames.last_mut() {
            Some(last) if last.frame == frame => last.points.push(point),
            Some(last) if frame < last.frame => {
                return Err(error(
                    number,
                    column(index[0]),
                    format!(
                        "frame {frame} after frame {}: expected the rows of a frame together, frames increasing",
                        last.frame
                    ),
                ));
            }
            _ => {
                frames.push(FramePoints { frame, time: number_at(index[1])?, points: vec![point] })
            }
        }
    }
    Ok(frames)
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
