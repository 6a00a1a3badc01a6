//! The knot type, agreement, knotted core and handedness of every frame of a hagfish run,
//! read from the run's `centreline.csv` (`frame,time_s,body,x_cm,y_cm,z_cm`, body 0 the
//! head), with nothing but this crate and the standard library:
//!
//! ```text
//! hagfish run data/scenarios/thesis.ron --out runs/thesis
//! cargo run --release -p hagfish-knots --example knot_of_a_run -- runs/thesis/centreline.csv 10
//! ```
//!
//! The optional second argument analyses every k-th frame (default 10). Output: one line per
//! analysed frame, `time_s knot agreement core_first core_last writhe`, the core as body
//! indices from the head. Any polyline source works the same way: one `Vec<DVec3>` per curve.

use std::error::Error;
use std::fs::File;
use std::io::{BufRead, BufReader};

use glam::DVec3;
use hagfish_knots::{KnotAnalyser, KnotOptions};

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let Some(path) = args.next() else {
        return Err("usage: knot_of_a_run <centreline.csv> [every k-th frame]".into());
    };
    let every: usize = args.next().map_or(Ok(10), |k| k.parse())?;
    if every == 0 {
        return Err("analyse every k-th frame with k ≥ 1".into());
    }
    let options = KnotOptions { extent: true, ..KnotOptions::default() };
    let mut analyser = KnotAnalyser::default();
    println!("time_s knot agreement core_first core_last writhe");
    for (time, points) in frames(&path)?.into_iter().step_by(every) {
        let report = analyser.analyse(&points, &options)?;
        let (first, last) =
            report.extent.map_or(("-".into(), "-".into()), |(a, b)| (a.to_string(), b.to_string()));
        let writhe = report.writhe.map_or("-".into(), |w| format!("{w:+.2}"));
        println!("{time:.2} {} {:.2} {first} {last} {writhe}", report.knot, report.agreement);
    }
    Ok(())
}

/// A recorded frame: its time (s) and the body centres (cm), head first.
type Frame = (f64, Vec<DVec3>);

/// Every frame of `path`, in file order.
fn frames(path: &str) -> Result<Vec<Frame>, Box<dyn Error>> {
    let mut frames: Vec<(u64, f64, Vec<DVec3>)> = Vec::new();
    for (number, line) in BufReader::new(File::open(path)?).lines().enumerate().skip(1) {
        let line = line?;
        let fields: Vec<&str> = line.split(',').collect();
        let [frame, time, _body, x, y, z] = fields[..] else {
            return Err(format!(
                "{path}:{}: expected 6 columns, found {}",
                number + 1,
                fields.len()
            )
            .into());
        };
        let (frame, time): (u64, f64) = (frame.parse()?, time.parse()?);
        let point = DVec3::new(x.parse()?, y.parse()?, z.parse()?);
        match frames.last_mut() {
            Some((last, _, points)) if *last == frame => points.push(point),
            _ => frames.push((frame, time, vec![point])),
        }
    }
    Ok(frames.into_iter().map(|(_, time, points)| (time, points)).collect())
}
