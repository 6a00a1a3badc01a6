//! The three entry points — [`render`], [`report`], [`write_all`] — over one run directory,
//! with what each wrote and how long each part took.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::error::ReportError;
use crate::run_dir::RunDir;
use crate::section::Section;
use crate::{animation, glb, html, obstacles, plots, vtk};

/// Name of the animated GIF in the run directory.
pub const ANIMATION: &str = "animation.gif";
/// Name of the glTF binary in the run directory.
pub const GLB: &str = "run.glb";
/// Name of the report in the run directory.
pub const REPORT: &str = "report.html";
/// Directory of the plots in the run directory.
pub const PLOTS: &str = "plots";
/// Directory of the VTK frames in the run directory.
pub const VTK: &str = "vtk";

/// What one entry point wrote.
#[derive(Clone, Debug, Default)]
pub struct Written {
    /// The files written (VTK frames counted in `vtk_frames`, not listed).
    pub files: Vec<PathBuf>,
    /// Number of VTK frame files written.
    pub vtk_frames: usize,
    /// Wall time of each part (name, seconds), in order.
    pub timings: Vec<(&'static str, f64)>,
}

impl Written {
    /// Runs `part`, recording its wall time under `name`.
    fn time<T>(&mut self, name: &'static str, part: impl FnOnce() -> T) -> T {
        let started = Instant::now();
        let value = part();
        self.timings.push((name, started.elapsed().as_secs_f64()));
        value
    }

    /// Total wall time (s).
    pub fn total_seconds(&self) -> f64 {
        self.timings.iter().map(|t| t.1).sum()
    }
}

/// The files the report crate has written into run directory `dir` (those that exist): the
/// animation, glTF and report, the plots in `plots/` and the frames and series in `vtk/` — and
/// nothing else, so that replacing a run never touches a user's files.
pub fn own_files(dir: &Path) -> Result<Vec<PathBuf>, ReportError> {
    let mut files: Vec<PathBuf> = [ANIMATION, GLB, REPORT]
        .iter()
        .map(|name| dir.join(name))
        .filter(|path| path.symlink_metadata().is_ok())
        .collect();
    files.extend(own_files_in(&own_subdirectory(dir, PLOTS)?, plots::is_own_file)?);
    files.extend(own_files_in(&own_subdirectory(dir, VTK)?, vtk::is_own_file)?);
    Ok(files)
}

/// `dir/name` (`plots/` or `vtk/`), refused if it is a symbolic link: the program writes and
/// removes its files only in a directory of the run's own, never through a link to another.
///
/// # Errors
/// [`ReportError::Write`] naming the link.
pub fn own_subdirectory(dir: &Path, name: &str) -> Result<PathBuf, ReportError> {
    let path = dir.join(name);
    if path.symlink_metadata().is_ok_and(|m| m.file_type().is_symlink()) {
        let what = "is a symbolic link; the program writes its files only into a directory of \
                    the run's own: remove the link (or replace it with a directory)";
        return Err(ReportError::write(&path)(std::io::Error::other(what)));
    }
    Ok(path)
}

/// The entries of `dir` (none if it does not exist) whose names `own` accepts, sorted.
pub(crate) fn own_files_in(dir: &Path, own: fn(&str) -> bool) -> Result<Vec<PathBuf>, ReportError> {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(ReportError::write(dir)(e)),
    };
    let mut files = Vec::new();
    for entry in entries {
        let entry = entry.map_err(ReportError::write(dir))?;
        if entry.file_name().to_str().is_some_and(own) {
            files.push(entry.path());
        }
    }
    files.sort();
    Ok(files)
}

/// Writes `bytes` as `path` atomically, replacing a file or link of that name and never
/// writing through a link ([`hagfish_run::replace_file`]).
pub(crate) fn write_file(path: &Path, bytes: &[u8]) -> Result<(), ReportError> {
    hagfish_run::replace_file(path, bytes).map_err(|e| match e {
        hagfish_run::RunError::Output { source, .. } => ReportError::write(path)(source),
        other => ReportError::write(path)(std::io::Error::other(other.to_string())),
    })
}

/// Which outputs to make.
#[derive(Clone, Copy, Debug)]
struct Parts {
    pictures: bool,
    exports: bool,
    report: bool,
}

fn make(dir: &Path, parts: Parts, sections: &[Section]) -> Result<Written, ReportError> {
    let mut written = Written::default();
    let (plot_dir, vtk_dir) = (own_subdirectory(dir, PLOTS)?, own_subdirectory(dir, VTK)?);
    let run = written.time("read", || RunDir::read(dir))?;
    let drawn = written.time("plots", || plots::draw(&run, &plot_dir))?;
    let gif_path = dir.join(ANIMATION);
    let gif = written.time("animation", || animation::encode(&run, &gif_path))?;
    if parts.pictures {
        written.files.extend(plots::write(&drawn, &plot_dir)?);
        write_file(&gif_path, &gif)?;
        written.files.push(gif_path);
    }
    if parts.exports {
        let tracks = obstacles::tracks(&run);
        let obstacles = match tracks.iter().any(|track| !track.poses.is_empty()) {
            false => vtk::ObstacleFrames::Still(obstacles::at_frame(&tracks, 0)),
            true => vtk::ObstacleFrames::Moving(
                (0..run.centreline.frames()).map(|f| obstacles::at_frame(&tracks, f)).collect(),
            ),
        };
        let radii = &run.radii.values;
        let (series, frames) =
            written.time("vtk", || vtk::write(&run.centreline, radii, &obstacles, &vtk_dir))?;
        written.files.push(series);
        written.vtk_frames = frames;
        let path = dir.join(GLB);
        let bytes = written.time("glb", || glb::encode(&run.centreline, radii, &tracks));
        write_file(&path, &bytes)?;
        written.files.push(path);
    }
    if parts.report {
        let path = dir.join(REPORT);
        let page = written.time("report", || html::page(&run, &drawn, &gif, sections));
        write_file(&path, page.as_bytes())?;
        written.files.push(path);
    }
    Ok(written)
}

/// `hagfish render DIR`: the plots (`plots/*.png`, `plots/*.svg`), `animation.gif`, the
/// ParaView frames (`vtk/`) and `run.glb`.
pub fn render(dir: &Path) -> Result<Written, ReportError> {
    make(dir, Parts { pictures: true, exports: true, report: false }, &[])
}

/// `hagfish report DIR`: `report.html` alone (its pictures drawn afresh, in memory), with
/// `sections` made by other crates after the plots.
pub fn report(dir: &Path, sections: &[Section]) -> Result<Written, ReportError> {
    make(dir, Parts { pictures: false, exports: false, report: true }, sections)
}

/// Everything [`render`] and [`report`] write, reading and drawing once.
pub fn write_all(dir: &Path, sections: &[Section]) -> Result<Written, ReportError> {
    make(dir, Parts { pictures: true, exports: true, report: true }, sections)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_files::synthetic;

    #[test]
    fn render_and_report_write_their_own_files_and_write_all_both() {
        let dir = synthetic("outputs");
        let stale = dir.join(VTK).join("frame_0099.vtk");
        std::fs::create_dir_all(dir.join(VTK)).expect("vtk/");
        std::fs::write(&stale, "from a longer run").expect("write");
        let rendered = render(&dir).expect("render");
        assert!(!stale.exists(), "a frame of an earlier run lingers");
        assert_eq!(rendered.files.len(), 10 + 3, "plots ×2, gif, series, glb");
        assert_eq!(rendered.vtk_frames, 3);
        assert!(dir.join(VTK).join("frame_0002.vtk").exists());
        assert!(!dir.join(REPORT).exists());
        let names: Vec<&str> = rendered.timings.iter().map(|t| t.0).collect();
        assert_eq!(names, ["read", "plots", "animation", "vtk", "glb"]);

        let reported = report(&dir, &[]).expect("report");
        assert_eq!(reported.files, vec![dir.join(REPORT)]);
        let all = write_all(&dir, &[]).expect("write_all");
        assert_eq!(all.files.len(), rendered.files.len() + 1);
        assert!(all.total_seconds() > 0.0);
    }

    #[test]
    fn a_linked_plots_or_vtk_directory_is_refused_and_not_written_through() {
        for name in [PLOTS, VTK] {
            let dir = synthetic(&format!("linked_{name}"));
            let elsewhere = dir.join("elsewhere");
            std::fs::create_dir_all(&elsewhere).expect("mkdir");
            std::fs::write(elsewhere.join("frame_0000.vtk"), "not the run's").expect("write");
            let _ = std::fs::remove_dir_all(dir.join(name));
            std::os::unix::fs::symlink(&elsewhere, dir.join(name)).expect("symlink");
            let error = write_all(&dir, &[]).expect_err("a link").to_string();
            assert!(error.contains("is a symbolic link"), "{error}");
            assert!(own_files(&dir).is_err(), "{name}: listed through the link");
            let entries = std::fs::read_dir(&elsewhere).expect("read").count();
            assert_eq!(entries, 1, "{name}: written through the link");
            assert!(!dir.join(REPORT).exists());
        }
    }
}
