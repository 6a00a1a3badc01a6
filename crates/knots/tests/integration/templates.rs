//! The follow-the-leader tie's templates (`data/knots/templates/`, made by
//! `bench/knot_templates.py`) are the knots they are named for: the analysis of each open
//! template, and of its mirror image, gives the knot's tabulated Alexander polynomial and
//! determinant (KnotInfo: 3₁ t² − t + 1, 4₁ t² − 3t + 1, 6₂ t⁴ − 3t³ + 3t² − 3t + 1), with
//! agreement ≥ 0.9 over the closure directions, and the chiral ones change handedness in the
//! mirror.

use std::path::Path;

use glam::DVec3;
use hagfish_knots::{KnotOptions, KnotType, analyse_knot};

/// The vertices of a template file (x y z per line, `#` comments).
fn template(name: &str) -> Vec<DVec3> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/knots/templates").join(name);
    let text = std::fs::read_to_string(&path).expect("a template file");
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().expect("a number")).collect();
            DVec3::new(v[0], v[1], v[2])
        })
        .collect()
}

#[test]
fn each_template_and_its_mirror_image_has_its_knots_tabulated_polynomial() {
    let cases: [(&str, KnotType, &[i64], u64, bool); 3] = [
        ("3_1.txt", KnotType::Trefoil, &[1, -1, 1], 3, true),
        ("4_1.txt", KnotType::FigureEight, &[1, -3, 1], 5, false),
        ("6_2.txt", KnotType::Knot6_2, &[1, -3, 3, -3, 1], 11, true),
    ];
    let options = KnotOptions::default();
    for (file, knot, coefficients, determinant, chiral) in cases {
        let curve = template(file);
        let mirror: Vec<DVec3> = curve.iter().map(|p| *p * DVec3::new(1.0, 1.0, -1.0)).collect();
        let reports = [&curve, &mirror].map(|c| analyse_knot(c, &options).expect(file));
        for report in &reports {
            assert_eq!(report.knot, knot, "{file}: {report:?}");
            assert_eq!(report.polynomial.coefficients(), coefficients, "{file}");
            assert_eq!(report.determinant, determinant, "{file}");
            assert!(report.agreement >= 0.9, "{file}: {report:?}");
        }
        if chiral {
            let [plain, mirrored] = reports.map(|r| r.right_handed());
            assert!(plain.is_some(), "{file}: a chiral knot has a handedness");
            assert_eq!(mirrored, plain.map(|r| !r), "{file}: the mirror turns the other way");
        }
    }
}
