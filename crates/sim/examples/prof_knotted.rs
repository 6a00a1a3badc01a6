use hagfish_control::WaterDrag;
use hagfish_sim::{DynamicsBackend, StepOptions, World, knotted_world};
fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let (world, _) = knotted_world(&root).unwrap();
    let sparse = std::env::args().any(|a| a == "sparse");
    let steps: usize = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(20);
    let options = StepOptions {
        backend: if sparse {
            DynamicsBackend::SparseMaximal
        } else {
            DynamicsBackend::DenseReduced
        },
        ..world.options().clone()
    };
    let mut w = World::new(world.model().clone(), options, world.state().clone()).unwrap();
    let mut drag = WaterDrag::default();
    w.step(&mut drag).unwrap();
    let start = world.state().clone();
    let mut stages = vec![Vec::new(); 8];
    let mut total = Vec::new();
    for _ in 0..(steps / 20).max(1) {
        w.set_state(start.clone()).unwrap();
        timed_steps(&mut w, &mut drag, &mut stages, &mut total);
    }
    let med = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2] * 1e6
    };
    let names: Vec<_> =
        hagfish_sim::StageTimings::default().stages().iter().map(|(n, _)| *n).collect();
    for (n, v) in names.iter().zip(stages.iter_mut()) {
        if !v.is_empty() {
            eprint!("{n} {:.1} ", med(v));
        }
    }
    eprintln!("total {:.1}", med(&mut total));
}
#[inline(never)]
fn timed_steps(w: &mut World, drag: &mut WaterDrag, stages: &mut [Vec<f64>], total: &mut Vec<f64>) {
    for _ in 0..20 {
        let t = std::time::Instant::now();
        let r = w.step(drag).unwrap();
        if std::env::var("DET").is_ok() {
            eprintln!("{:?}", r.detection);
        }
        total.push(t.elapsed().as_secs_f64());
        for (s, (_, x)) in stages.iter_mut().zip(r.timings.stages()) {
            s.push(x);
        }
    }
}
