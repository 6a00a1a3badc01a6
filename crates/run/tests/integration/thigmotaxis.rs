//! Thigmotaxic inverse dynamics, end to end at h = 0.01 s: the scenarios
//! `thesis_scripted.ron` (form → tighten → slide to the head), `loosen.ron` and `reverse.ron` run in
//! full and their frames are checked against the thesis' claims.
//!
//! The thigmotaxis phases amplify rounding (contacts appear and vanish at the margin), so each
//! scenario is run as written **and** with its time step changed by 1 to 7 parts in 10¹²: a
//! rounding-level perturbation, like another CPU's SIMD width. Every claim is checked on every
//! run, so none holds by the luck of one trajectory; the slide's force growth, which holds in
//! ≈ 95 % of trajectories, is asked of 6 of the 8.
//!
//! The knot's span is the stretch of body its self contacts cover ([`KnotSpan`]), its
//! position that stretch's midpoint. Both flicker by 1–2 cm between frames as contacts at the
//! knot's ends appear and vanish at the margin, so spans and positions are 0.5 s means.

use crate::freshly_tied::{Thigmo, freshly_tied_knot, thigmo_step};
use glam::DVec3;
use hagfish_control::{ForceSpace, KnotSpan, SlidingTargets, ThigmoParameters};
use hagfish_knots::KnotType;
use hagfish_run::{Frame, FrameSink, RunError, RunOptions, RunSummary};
use hagfish_scenario::LoadedScenario;
use hagfish_sim::rows::{RowGroup, twist_dofs};

use hagfish_tree::{Data, Model, position_kinematics};

/// Relative changes of the time step: the scenario as written, then seven rounding-level
/// perturbations.
const PERTURBATIONS: [f64; 8] = [0.0, 1e-12, 2e-12, 3e-12, 4e-12, 5e-12, 6e-12, 7e-12];

/// What the checks need of one frame.
#[derive(Clone, Debug)]
struct Record {
    time: f64,
    phase: String,
    span: Option<KnotSpan>,
    trefoil: bool,
    penetration_relative: f64,
    slack_rows: usize,
    head: DVec3,
}

/// The recorded frames, and what places the head point of each.
struct Records {
    frames: Vec<Record>,
    model: Model,
    data: Data,
}

/// A point on the head body's surface, off its twist (X) axis, in the body's frame (cm): the
/// body's centre lies on the root revolute axis, so only an off-axis point shows a twist of
/// the head.
const HEAD_POINT: DVec3 = DVec3::new(0.212, 0.89, 0.0);

impl FrameSink for Records {
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), RunError> {
        position_kinematics(&self.model, &frame.state.q, &mut self.data);
        self.frames.push(Record {
            time: frame.time,
            phase: frame.phase.to_string(),
            span: frame.span,
            trefoil: frame.knot.is_some_and(|k| k.knot == KnotType::Trefoil),
            penetration_relative: frame.maxima.self_penetration_relative,
            slack_rows: frame.step.solve.slack.count,
            head: self.data.body_frames[0].transform_point(HEAD_POINT),
        });
        Ok(())
    }
}

/// Runs scenario `name` with its time step scaled by `1 + perturbation`.
fn run(name: &str, perturbation: f64) -> (Vec<Record>, RunSummary) {
    let path = format!("{}/../../data/scenarios/{name}.ron", env!("CARGO_MANIFEST_DIR"));
    let mut loaded = LoadedScenario::load(&path).expect("scenario loads");
    loaded.scenario.time_step_s *= 1.0 + perturbation;
    let model = loaded.body.to_model().expect("model builds");
    let data = Data::new(&model);
    let mut records = Records { frames: Vec::new(), model, data };
    let outcome = hagfish_run::run(&loaded, RunOptions::default(), &mut records, &mut |_| {})
        .unwrap_or_else(|e| panic!("{name}: run does not start: {e}"));
    let summary = outcome.finished().unwrap_or_else(|e| {
        panic!("{name} (δh/h = {perturbation:e}): run diverged (a failed solve stops the run): {e}")
    });
    (records.frames, summary)
}

fn phase<'a>(records: &'a [Record], name: &str) -> Vec<&'a Record> {
    let frames: Vec<&Record> = records.iter().filter(|r| r.phase == name).collect();
    assert!(frames.len() > 5, "phase {name} has {} frames", frames.len());
    frames
}

/// Mean of `measure` over the frames with contacts in `[from, to]` s.
fn mean_over(
    frames: &[&Record],
    from: f64,
    to: f64,
    measure: impl Fn(&KnotSpan) -> f64,
) -> Option<f64> {
    let values: Vec<f64> = frames
        .iter()
        .filter(|r| r.time >= from - 1e-9 && r.time <= to + 1e-9)
        .filter_map(|r| r.span.as_ref().map(&measure))
        .collect();
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

/// `measure` averaged over the first and over the last 0.5 s of a phase.
fn first_and_last(frames: &[&Record], measure: impl Fn(&KnotSpan) -> f64) -> (f64, f64) {
    let (t0, t1) = (frames[0].time, frames[frames.len() - 1].time);
    let first = mean_over(frames, t0, t0 + 0.5, &measure).expect("contacts in the first 0.5 s");
    let last = mean_over(frames, t1 - 0.5, t1, &measure).expect("contacts in the last 0.5 s");
    (first, last)
}

/// The span (cm) over the first and the last 0.5 s of a phase, printed after `label`.
fn span_change(frames: &[&Record], label: &str) -> (f64, f64) {
    let (before, after) = first_and_last(frames, KnotSpan::length_cm);
    println!(
        "{label}: span {before:.2} → {after:.2} cm ({:+.1} %)",
        100.0 * (after / before - 1.0)
    );
    (before, after)
}

/// Largest tail-ward move of the knot's position (its 0.5 s mean) within any 1 s window (cm),
/// and the same for single frames (reported: it measures the flicker of the contacts at the
/// knot's ends as much as the knot).
fn worst_tailward_move(frames: &[&Record]) -> (f64, f64) {
    let worst = |positions: &[(f64, f64)]| {
        let mut worst = 0.0_f64;
        for (i, &(t, x)) in positions.iter().enumerate() {
            for &(_, later) in positions[i..].iter().take_while(|(t2, _)| *t2 <= t + 1.0 + 1e-9) {
                worst = worst.max(later - x);
            }
        }
        worst
    };
    let raw: Vec<(f64, f64)> =
        frames.iter().filter_map(|r| r.span.map(|s| (r.time, s.midpoint_cm()))).collect();
    let smooth: Vec<(f64, f64)> = raw
        .iter()
        .filter_map(|&(t, _)| {
            mean_over(frames, t - 0.25, t + 0.25, KnotSpan::midpoint_cm).map(|x| (t, x))
        })
        .collect();
    (worst(&smooth), worst(&raw))
}

fn trefoil_fraction(frames: &[&Record]) -> f64 {
    frames.iter().filter(|r| r.trefoil).count() as f64 / frames.len() as f64
}

fn max_penetration(records: &[Record]) -> f64 {
    records.iter().map(|r| r.penetration_relative).fold(0.0, f64::max)
}

fn head_drift(records: &[Record]) -> f64 {
    records.iter().map(|r| (r.head - records[0].head).length()).fold(0.0, f64::max)
}

/// Runs of the eight in which the slide's force must grow as the knot nears the head. The
/// growth holds in ≈ 95 % of trajectories, not in all: over 48 rounding perturbations the last
/// quarter's mean |f| is below the first's in 3 on the dense backend and 2 on the sparse one
/// (docs/physics.md, "More force as the knot nears the head"). At that rate 6 of 8 fails once in
/// ≈ 100 reruns under other rounding; without the growth (one run in two) it passes one in seven.
const FORCE_GROWTH_RUNS: usize = 6;

#[test]
fn thesis_tightens_then_slides_the_knot_to_the_head() {
    let grown: Vec<(f64, bool)> = PERTURBATIONS
        .iter()
        .map(|&perturbation| (perturbation, check_thesis(perturbation)))
        .collect();
    let count = grown.iter().filter(|(_, grows)| *grows).count();
    assert!(
        count >= FORCE_GROWTH_RUNS,
        "the force grows as the knot nears the head in {count} of 8 runs: {grown:?}"
    );
}

/// Checks one run of the thesis (scripted knot) and returns whether the force over the slide
/// grew from its first quarter to its last.
fn check_thesis(perturbation: f64) -> bool {
    let (records, summary) = run("thesis_scripted", perturbation);
    let label = format!("thesis, δh/h = {perturbation:e}");

    let tighten = phase(&records, "tighten");
    let (before, after) = span_change(&tighten, &format!("{label}: tighten"));
    assert!(after <= 0.8 * before, "{label}: tightening shrinks the span by ≥ 20 %");

    let slide = phase(&records, "slide");
    let (t0, t1) = (slide[0].time, slide[slide.len() - 1].time);
    let (from, to) = first_and_last(&slide, |s| s.start_cm);
    let (mid_from, mid_to) = first_and_last(&slide, KnotSpan::midpoint_cm);
    let speed = (mid_from - mid_to) / (t1 - t0 - 0.5);
    let head_region = 3.0;
    let covered = (from - to) / (from - head_region);
    let (worst, worst_single) = worst_tailward_move(&slide);
    let checked: Vec<&Record> = tighten.iter().chain(&slide).copied().collect();
    let trefoil = trefoil_fraction(&checked);
    let slack_frames = slide.iter().filter(|r| r.slack_rows > 0).count();
    println!(
        "{label}: slide: knot start {from:.2} → {to:.2} cm in {:.1} s ({:.0} % of the way to \
         {head_region} cm), position speed {speed:.2} cm/s, worst 1 s tail-ward move {worst:.2} cm \
         (single frames {worst_single:.2} cm), trefoil in {:.1} % of {} frames, frames using \
         slack {slack_frames}/{}",
        t1 - t0,
        100.0 * covered,
        100.0 * trefoil,
        checked.len(),
        slide.len()
    );
    assert!(covered >= 0.5, "{label}: the knot covers ≥ 50 % of the way to the head: {covered}");
    assert!((1.0..=4.0).contains(&speed), "{label}: mean speed within 2× of 2 cm/s: {speed}");
    assert!(worst <= 0.5, "{label}: no 1 s window moves the knot tail-ward by > 0.5 cm: {worst}");
    assert!(trefoil >= 0.99, "{label}: trefoil in ≥ 99 % of checked frames: {trefoil}");

    let penetration = max_penetration(&records);
    let drift = head_drift(&records);
    println!(
        "{label}: whole run: max penetration {:.2} % of r, head drift {drift:.2e} cm",
        100.0 * penetration
    );
    assert!(penetration < 0.02, "{label}: penetration {penetration} of the radius");
    assert!(drift < 1e-6, "{label}: the head stays fixed: {drift} cm");

    // Force field (thesis §6.3).
    let stats = summary.force_field.stats("slide").expect("slide frames");
    println!("{label}: force field over the slide: {stats:?}");
    assert!(stats.tailward_samples > 0, "{label}: the knot has joints tail-ward of it");
    assert!(
        stats.tailward_zero_fraction >= 0.95,
        "{label}: zero force tail-ward of the knot in ≥ 95 % of samples: {}",
        stats.tailward_zero_fraction
    );
    stats.last_quarter_mean_dyn_cm > stats.first_quarter_mean_dyn_cm
}

#[test]
fn loosening_grows_the_span() {
    for perturbation in PERTURBATIONS {
        let (records, _) = run("loosen", perturbation);
        let label = format!("loosen, δh/h = {perturbation:e}");
        let loosen = phase(&records, "loosen");
        let (before, after) = span_change(&loosen, &label);
        assert!(after >= 1.2 * before, "{label}: loosening grows the span by ≥ 20 %");
        assert!(trefoil_fraction(&loosen) >= 0.99, "{label}: still a trefoil");
        let penetration = max_penetration(&records);
        assert!(penetration < 0.02, "{label}: penetration {penetration}");
    }
}

#[test]
fn negative_targets_slide_the_knot_tail_ward() {
    for perturbation in PERTURBATIONS {
        let (records, _) = run("reverse", perturbation);
        let label = format!("reverse, δh/h = {perturbation:e}");
        let reverse = phase(&records, "reverse");
        let (from, to) = first_and_last(&reverse, KnotSpan::midpoint_cm);
        let trefoil = trefoil_fraction(&reverse);
        println!(
            "{label}: knot position {from:.2} → {to:.2} cm, trefoil in {:.1} %",
            100.0 * trefoil
        );
        assert!(to - from >= 5.0, "{label}: the knot slides ≥ 5 cm tail-ward: {from} → {to}");
        assert!(trefoil >= 0.99, "{label}: trefoil kept: {trefoil}");
        let penetration = max_penetration(&records);
        assert!(penetration < 0.02, "{label}: penetration {penetration}");
    }
}

/// Row signs: in a freshly tied knot (form.ron at 17 s), one step of thigmotaxis on the first
/// and last contact, with positive and with negative targets, achieves each row's relative
/// tangential speed `cᵀq̇ ≥ |v|` (a row the solver could not satisfy must report slack) with
/// λ ≥ 0; and a negative target's row is exactly the positive one's negated (the strands slide
/// head-ward relative to each other instead of tail-ward).
#[test]
fn thigmo_rows_reach_their_speeds_with_nonnegative_multipliers() {
    let (_, mut world, knotted) = freshly_tied_knot();
    let mut positive_rows: Vec<Vec<f64>> = Vec::new();
    for speed in [1.0, -1.0] {
        world.set_state(knotted.clone()).expect("state restores");
        let targets = SlidingTargets { v_a: speed, v_b: speed };
        let parameters = ThigmoParameters {
            head: targets,
            tail: targets,
            tail_pull_dyn: 0.0,
            max_force_dyn: 1e6,
            force_space: ForceSpace::Full,
            replay: None,
        };
        let report = *world.step(&mut Thigmo(parameters)).expect("thigmo step");
        let data = world.data();
        let (qdot, lambda) = (data.solver.velocity(), data.solver.multipliers());
        let mut thigmo_rows = 0;
        for (i, source) in data.rows.sources().iter().enumerate() {
            if source.tag != RowGroup::Thigmo.tag() {
                continue;
            }
            thigmo_rows += 1;
            let row = data.rows.row(i).expect("row exists").to_vec();
            if speed > 0.0 {
                positive_rows.push(row.to_vec());
            } else {
                let positive = &positive_rows[thigmo_rows - 1];
                assert!(row.iter().zip(positive).all(|(n, p)| *n == -*p), "row {i} is not negated");
            }
            let achieved: f64 = row.iter().zip(qdot).map(|(c, v)| c * v).sum();
            println!("v = {speed:+}: row {i}: achieved {achieved:.4} cm/s, λ = {:.3e}", lambda[i]);
            assert_eq!(data.rows.rhs()[i], speed.abs());
            assert!(lambda[i] >= 0.0, "λ = {} < 0", lambda[i]);
            assert!(
                achieved >= speed.abs() - 1e-6 || report.solve.slack.count > 0,
                "row {i} reaches only {achieved} cm/s of {} without reporting slack",
                speed.abs()
            );
        }
        assert_eq!(thigmo_rows, 4, "two rows on each of the first and last contact");
        assert_eq!(report.solve.slack.count, 0, "a 10⁶ dyn cap needs no slack");
    }
}

/// Bending-only thigmotaxis (`ForceSpace::BendingOnly`), from the same freshly tied knot as
/// above: each row is the full row with its twist entries zeroed (so the full rows do have
/// twist entries), and the step's thigmotaxic generalized force `C_thᵀλ` has no twist torque
/// at all while its bending torques are not zero.
#[test]
fn bending_only_rows_exert_no_twist_torque() {
    let (_, mut world, knotted) = freshly_tied_knot();
    let twist = twist_dofs(world.model());
    let mut rows_and_forces = Vec::new();
    for force_space in [ForceSpace::Full, ForceSpace::BendingOnly] {
        let force = thigmo_step(&mut world, &knotted, force_space);
        let data = world.data();
        let rows: Vec<Vec<f64>> = (0..data.rows.len())
            .filter(|&i| data.rows.sources()[i].tag == RowGroup::Thigmo.tag())
            .map(|i| data.rows.row(i).expect("row exists").to_vec().to_vec())
            .collect();
        rows_and_forces.push((rows, force));
    }
    let [(full_rows, full_force), (bending_rows, bending_force)] =
        <[_; 2]>::try_from(rows_and_forces).expect("two runs");
    assert_eq!(full_rows.len(), bending_rows.len());
    assert!(full_rows.iter().any(|row| twist.iter().any(|&k| row[k] != 0.0)), "no twist entry");
    for (full, bending) in full_rows.iter().zip(&bending_rows) {
        for (k, (f, b)) in full.iter().zip(bending).enumerate() {
            let expected = if twist.contains(&k) { 0.0 } else { *f };
            assert_eq!(*b, expected, "DOF {k}");
        }
    }
    assert!(twist.iter().any(|&k| full_force[k] != 0.0), "the full force twists");
    assert!(twist.iter().all(|&k| bending_force[k] == 0.0), "{bending_force:?}");
    assert!(bending_force.iter().any(|f| f.abs() > 1.0), "bending torques of a dyn·cm or more");
}
