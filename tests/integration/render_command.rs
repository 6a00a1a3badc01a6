//! `hagfish run` on a 1 s copy of form.ron also writes the pictures, the report and the
//! exports; `hagfish render DIR` and `hagfish report DIR` re-make them from the directory;
//! a directory without its CSV files is exit code 2 naming the file; and report.html
//! renders in headless Chromium: images decoded, WebGL view drawn, no script error.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Runs `hagfish ARGS…` and returns its output.
fn hagfish(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hagfish"))
        .args(args)
        .arg(dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run hagfish: {e}"))
}

/// A fresh run directory `name`: form.ron shortened to 1 s (11 frames) run by
/// `hagfish run`, with that scenario copied in as `scenario.ron` (its body path absolute, so
/// the radii come from the biometrics).
fn short_run(name: &str) -> PathBuf {
    let tmp = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let dir = tmp.join(name);
    let _ = std::fs::remove_dir_all(&dir);
    let form =
        std::fs::read_to_string(format!("{ROOT}/data/scenarios/form.ron")).expect("form.ron");
    let body = format!("body: \"{ROOT}/data/hagfish/es103.ron\"");
    let short = form
        .replace("duration_s: 30.0", "duration_s: 1.0")
        .replace("body: \"../hagfish/es103.ron\"", &body);
    assert!(short.contains("duration_s: 1.0") && short.contains(&body), "form.ron changed shape");
    let scenario = tmp.join(format!("{name}.ron"));
    std::fs::write(&scenario, &short).expect("write the scenario");
    let output = Command::new(env!("CARGO_BIN_EXE_hagfish"))
        .arg("run")
        .arg(&scenario)
        .args(["--quiet", "--out"])
        .arg(&dir)
        .output()
        .expect("hagfish runs");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    std::fs::write(dir.join("scenario.ron"), &short).expect("copy the scenario");
    dir
}

/// The outputs of `hagfish render` and `hagfish report`, relative to the run directory.
const OUTPUTS: [&str; 15] = [
    "plots/kymograph_x.png",
    "plots/kymograph_x.svg",
    "plots/kymograph_y.png",
    "plots/kymograph_y.svg",
    "plots/kymograph_z.png",
    "plots/kymograph_z.svg",
    "plots/knot_span.png",
    "plots/knot_span.svg",
    "plots/contacts.png",
    "plots/contacts.svg",
    "animation.gif",
    "vtk/centreline.vtk.series",
    "vtk/frame_0010.vtk",
    "run.glb",
    "report.html",
];

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Checks each output's signature: PNG, SVG, GIF, VTK, the series, glTF and HTML.
fn assert_outputs(dir: &Path) {
    for name in OUTPUTS {
        let bytes = read(&dir.join(name));
        let text = String::from_utf8_lossy(&bytes[..bytes.len().min(64)]).to_string();
        let ok = match Path::new(name).extension().and_then(|e| e.to_str()) {
            Some("png") => bytes.starts_with(b"\x89PNG"),
            Some("svg") => text.starts_with("<svg"),
            Some("gif") => bytes.starts_with(b"GIF89a"),
            Some("vtk") => text.starts_with("# vtk DataFile Version 3.0"),
            Some("series") => text.contains("file-series-version"),
            Some("glb") => bytes.starts_with(b"glTF"),
            _ => text.starts_with("<!DOCTYPE html>"),
        };
        assert!(ok, "{name} starts with {text:?}");
    }
    assert!(!dir.join("vtk/frame_0011.vtk").exists(), "11 frames: 0 … 10");
}

#[test]
fn run_writes_everything_and_render_and_report_remake_it() {
    let dir = short_run("render_short");
    assert_outputs(&dir);

    for name in OUTPUTS {
        std::fs::remove_file(dir.join(name)).expect("remove");
    }
    let render = hagfish(&["render"], &dir);
    assert!(render.status.success(), "{}", String::from_utf8_lossy(&render.stderr));
    assert!(!dir.join("report.html").exists(), "render does not write the report");
    let report = hagfish(&["report"], &dir);
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    assert_outputs(&dir);
    let html = String::from_utf8(read(&dir.join("report.html"))).expect("UTF-8");
    assert!(html.contains("the body file named by"), "radii from scenario.ron's body file");
    assert!(html.contains("Scenario(") && html.contains("duration_s: 1.0"), "scenario text");
    assert!(!html.contains("<section id=\"modes\">"), "a Form phase has no thigmotaxic force");
    let stdout = String::from_utf8_lossy(&report.stdout);
    assert!(stdout.contains("report.html") && stdout.contains("total"), "{stdout}");
}

#[test]
fn a_directory_without_its_csv_files_is_exit_code_2_naming_the_file() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("render_empty");
    std::fs::create_dir_all(&dir).expect("dir");
    for command in ["render", "report"] {
        let output = hagfish(&[command], &dir);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        assert!(stderr.starts_with("error: ") && stderr.contains("centreline.csv"), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// The Chromium binary: `HAGFISH_CHROMIUM` (set by `cargo xtask test`, which finds or
/// installs it), else `chromium` on PATH or in /usr/bin (Debian's package).
fn chromium() -> PathBuf {
    if let Some(given) = std::env::var_os("HAGFISH_CHROMIUM") {
        return PathBuf::from(given);
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .chain([PathBuf::from("/usr/bin")])
        .map(|d| d.join("chromium"))
        .find(|p| p.is_file())
        .unwrap_or_else(|| {
            panic!(
                "chromium not found: run the tests with `cargo xtask test`, which installs it, \
                 or install Debian's chromium, or set HAGFISH_CHROMIUM"
            )
        })
}

/// The value of attribute `name` in the first `<tag …>` of `html`.
fn attribute(html: &str, tag: &str, name: &str) -> Option<String> {
    let start = html.find(&format!("<{tag}"))?;
    let element = &html[start..start + html[start..].find('>')?];
    let key = format!("{name}=\"");
    let at = element.find(&key)? + key.len();
    Some(element[at..at + element[at..].find('"')?].to_string())
}

#[test]
fn report_html_renders_in_headless_chromium() {
    let dir = short_run("render_chromium");
    let profile = dir.join("chromium-profile");
    // Files, not pipes: the DOM is larger than a pipe's buffer, and nothing reads it before
    // chromium exits.
    let (dom_path, log_path) = (dir.join("dom.html"), dir.join("chromium.log"));
    let create =
        |p: &Path| std::fs::File::create(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    let mut child = Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--virtual-time-budget=5000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("file://{}", dir.join("report.html").display()))
        .stdout(Stdio::from(create(&dom_path)))
        .stderr(Stdio::from(create(&log_path)))
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start chromium: {e}"));
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for chromium") {
            break status;
        }
        if started.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("chromium did not finish within 120 s");
        }
        std::thread::sleep(Duration::from_millis(100));
    };
    let dom = String::from_utf8_lossy(&read(&dom_path)).to_string();
    let stderr = String::from_utf8_lossy(&read(&log_path)).to_string();
    assert!(status.success(), "chromium failed: {stderr}");
    let body =
        |name| attribute(&dom, "body", name).unwrap_or_else(|| panic!("no {name}: {stderr}"));
    let errors = attribute(&dom, "div id=\"errors\"", "data-count");
    assert_eq!(errors.as_deref(), Some("0"), "script errors recorded: {dom}");
    assert_eq!(
        body("data-plots"),
        "8/8",
        "seven plots (three force kymographs, knot span, contacts, tension kymograph, tension at \
         the head) and the animation decoded"
    );
    assert_eq!(body("data-animation"), "ok");
    assert_eq!(body("data-webgl"), "ok", "WebGL view: {stderr}");
    assert_eq!(body("data-status"), "ok");
    let pixels = attribute(&dom, "canvas", "data-drawn-pixels").and_then(|p| p.parse::<u32>().ok());
    assert!(pixels.is_some_and(|p| p > 1000), "the body covers the 3-D view: {pixels:?}");
    assert!(dom.contains("t = 1.00 s (frame 10 of 10, phase form, knot 0_1)"), "the view's label");
}
