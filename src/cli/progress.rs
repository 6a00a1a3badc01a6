//! Progress of `hagfish run` on stderr: a bar on a terminal (simulated time of the duration,
//! or of its cap for a run that ends with its phases; phase, knot, steps per second), plain
//! lines otherwise (one per simulated second, or after 2 s of wall time), nothing with
//! `--quiet`.

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

use hagfish_run::Progress;
use indicatif::{ProgressBar, ProgressStyle};

/// Wall time after which a plain line is printed even within a simulated second.
const LINE_EVERY: Duration = Duration::from_secs(2);

/// How progress is shown.
#[derive(Debug)]
enum Mode {
    Quiet,
    Bar(ProgressBar),
    Lines { last_second: f64, last_line: Instant },
}

/// Shows the progress of a run.
#[derive(Debug)]
pub struct Reporter {
    mode: Mode,
    started: Instant,
    first_steps: Option<u64>,
}

impl Reporter {
    /// A reporter for a run of `duration` simulated seconds: quiet, a bar when stderr is a
    /// terminal, plain lines otherwise.
    pub fn new(quiet: bool, duration: f64) -> Self {
        let mode = if quiet {
            Mode::Quiet
        } else if std::io::stderr().is_terminal() {
            let bar = ProgressBar::new((duration * 1000.0).round() as u64);
            let style = ProgressStyle::with_template("{bar:30.cyan/blue} {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            Mode::Bar(bar)
        } else {
            Mode::Lines { last_second: -1.0, last_line: Instant::now() }
        };
        Self { mode, started: Instant::now(), first_steps: None }
    }

    /// Shows `p`.
    pub fn update(&mut self, p: &Progress<'_>) {
        let first = *self.first_steps.get_or_insert(p.steps);
        let elapsed = self.started.elapsed().as_secs_f64();
        let rate = if elapsed > 0.0 { (p.steps - first) as f64 / elapsed } else { 0.0 };
        let message = message(p, rate);
        match &mut self.mode {
            Mode::Quiet => {}
            Mode::Bar(bar) => {
                bar.set_position((p.time * 1000.0).round() as u64);
                bar.set_message(message);
            }
            Mode::Lines { last_second, last_line } => {
                let second = p.time.floor();
                if second > *last_second || last_line.elapsed() >= LINE_EVERY {
                    *last_second = second;
                    *last_line = Instant::now();
                    // Nothing sensible is left to do if stderr itself is closed.
                    let _ = writeln!(std::io::stderr(), "{message}");
                }
            }
        }
    }

    /// Removes the bar (lines stay).
    pub fn finish(&self) {
        if let Mode::Bar(bar) = &self.mode {
            bar.finish_and_clear();
        }
    }
}

/// One progress line: simulated time against the duration (or its cap, for a run that ends
/// with its phases), phase, knot and steps per second.
fn message(p: &Progress<'_>, rate: f64) -> String {
    let knot = p.knot.map_or("?".to_string(), |k| format!("{} ({:.2})", k.knot, k.agreement));
    let horizon = if p.ends_with_phases {
        format!("(ends with its phases, at most {:.2} s)", p.duration)
    } else {
        format!("/ {:.2} s", p.duration)
    };
    format!("t = {:6.2} {horizon}  phase {:6}  knot {knot}  {rate:.0} steps/s", p.time, p.phase)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_that_ends_with_its_phases_shows_its_duration_as_a_cap() {
        let mut p = Progress {
            time: 12.3,
            duration: 90.0,
            ends_with_phases: true,
            frames: 123,
            steps: 1230,
            knot: None,
            phase: "slide",
        };
        let capped = message(&p, 900.0);
        assert_eq!(
            capped,
            "t =  12.30 (ends with its phases, at most 90.00 s)  phase slide   knot ?  900 steps/s"
        );
        p.ends_with_phases = false;
        assert!(message(&p, 900.0).starts_with("t =  12.30 / 90.00 s  phase slide"));
    }
}
