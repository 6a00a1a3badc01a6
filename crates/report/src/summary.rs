//! The report's summary table: a few numbers per run, computed from `metrics.csv` (and the
//! tension of `internal.csv` when the run has it).

use crate::metrics::Metrics;
use crate::tension::Tension;

/// (quantity, value) rows describing the run.
pub fn rows(m: &Metrics, tension: Option<&Tension>) -> Vec<(String, String)> {
    let last = m.frames() - 1;
    let max = |v: &[f64]| v.iter().fold(0.0, |a: f64, b| a.max(*b));
    let mut rows = vec![
        ("frames".to_string(), m.frames().to_string()),
        ("simulated time".to_string(), format!("{:.2} s", m.time[last])),
        ("phases".to_string(), phases(m)),
        (
            "final knot".to_string(),
            match m.knot_agreement[last] {
                Some(a) => format!("{} (agreement {a:.2})", m.knot[last]),
                None => m.knot[last].clone(),
            },
        ),
        (
            "knot first detected".to_string(),
            m.knot
                .iter()
                .position(|k| !k.is_empty() && k != "0_1")
                .map_or("never".to_string(), |f| format!("t = {:.2} s ({})", m.time[f], m.knot[f])),
        ),
        (
            "final knot position".to_string(),
            m.knot_position[last].map_or("–".to_string(), |p| format!("{p:.2} cm from the head")),
        ),
        ("max self contacts".to_string(), format!("{}", max(&m.self_contacts))),
        ("max wall contacts".to_string(), format!("{}", max(&m.wall_contacts))),
        (
            "max self penetration".to_string(),
            format!("{:.2} % of the local radius", 100.0 * max(&m.self_penetration_rel)),
        ),
        ("max wall penetration".to_string(), format!("{:.4} cm", max(&m.wall_penetration))),
        ("max joint-limit excess".to_string(), format!("{:.3}°", max(&m.limit_excess_deg))),
    ];
    let unsolved: Vec<&str> =
        m.solver_status.iter().filter(|s| *s != "Solved").map(String::as_str).collect();
    let mut kinds = unsolved.clone();
    kinds.sort_unstable();
    kinds.dedup();
    rows.push((
        "frames not Solved".to_string(),
        if unsolved.is_empty() {
            "0".to_string()
        } else {
            format!("{} ({})", unsolved.len(), kinds.join(", "))
        },
    ));
    if let Some(tension) = tension {
        let head = tension.at_head();
        let (final_n, peak) = (head.last().copied().unwrap_or(0.0), max(&head));
        let mean = head.iter().sum::<f64>() / head.len().max(1) as f64;
        rows.push((
            "tension at the head (the pull the body transmits)".to_string(),
            format!("final {final_n:.4e} dyn, max {peak:.4e} dyn, mean over frames {mean:.4e} dyn"),
        ));
    }
    rows
}

/// "form 0.00–12.30 s, thigmo 12.40–30.00 s": each run of equal phase with its times.
fn phases(m: &Metrics) -> String {
    let mut parts = Vec::new();
    let mut start = 0;
    for f in 1..=m.frames() {
        if f == m.frames() || m.phase[f] != m.phase[start] {
            parts.push(format!("{} {:.2}–{:.2} s", m.phase[start], m.time[start], m.time[f - 1]));
            start = f;
        }
    }
    parts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summarises_phases_knot_and_maxima() {
        let m = Metrics {
            time: vec![0.0, 0.1, 0.2],
            phase: ["form", "form", "thigmo"].map(String::from).to_vec(),
            knot: ["0_1", "3_1", "3_1"].map(String::from).to_vec(),
            knot_agreement: vec![Some(1.0), Some(0.5), Some(0.97)],
            solver_status: ["Solved", "SolvedInexact", "Solved"].map(String::from).to_vec(),
            self_contacts: vec![0.0, 4.0, 2.0],
            wall_contacts: vec![0.0, 1.0, 0.0],
            knot_position: vec![None, Some(20.0), Some(18.5)],
            self_penetration_rel: vec![0.0, 0.011, 0.002],
            wall_penetration: vec![0.0; 3],
            limit_excess_deg: vec![0.0, 0.25, 0.0],
            ..Metrics::default()
        };
        let rows = rows(&m, None);
        let get = |k: &str| rows.iter().find(|r| r.0 == k).map(|r| r.1.clone()).expect(k);
        assert_eq!(get("phases"), "form 0.00–0.10 s, thigmo 0.20–0.20 s");
        assert_eq!(get("final knot"), "3_1 (agreement 0.97)");
        assert_eq!(get("knot first detected"), "t = 0.10 s (3_1)");
        assert_eq!(get("final knot position"), "18.50 cm from the head");
        assert_eq!(get("max self contacts"), "4");
        assert_eq!(get("max self penetration"), "1.10 % of the local radius");
        assert_eq!(get("max joint-limit excess"), "0.250°");
        assert_eq!(get("frames not Solved"), "1 (SolvedInexact)");
    }
}
