fn main() {
    let root = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let arg = |k: usize| std::env::args().nth(k).and_then(|a| a.parse::<f64>().ok());
    let refinement = hagfish_validation::loose_knot::Refinement {
        bodies: arg(1).map(|n| n as usize),
        rod_radius_cm: arg(2),
        time_step_s: arg(3),
    };
    let clock = std::time::Instant::now();
    match hagfish_validation::loose_knot::run(root, 10.0, refinement) {
        Ok(k) => println!(
            "{refinement:?} TR2/B {:.5} out {:.4} twist {:.4} all {:.4} in {:.0} s",
            k.tension_number(k.loop_radius_cm()),
            k.worst_first_integral(|j| k.outside_braid[j]),
            k.worst_first_integral(|j| !k.bending_joint[j]),
            k.worst_first_integral(|_| true),
            clock.elapsed().as_secs_f64()
        ),
        Err(e) => println!("{refinement:?}: {e}"),
    }
}
