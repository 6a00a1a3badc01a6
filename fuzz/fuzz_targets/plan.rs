//! Plan files, the first byte choosing which: a sweep's grid file (`hagfish sweep plan
//! GRID`), a sweep folder's `plan.json` (`hagfish sweep run FOLDER`), or a knot plan named by
//! a tie phase (`Tie((knot: Planned((file: …))))` in `data/scenarios/tie.ron`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let Some((&kind, rest)) = data.split_first() else { return };
    match kind % 3 {
        0 => drop(hagfish::sweep::Grid::read(&hagfish_fuzz::write("sweep/grid.ron", rest))),
        1 => {
            hagfish_fuzz::write("sweep/plan.json", rest);
            drop(hagfish::sweep::Plan::read(&hagfish_fuzz::scratch().join("sweep")));
        }
        _ => {
            hagfish_fuzz::write("knots/fuzzed.ron", rest);
            let scenario = hagfish_fuzz::scratch().join("scenarios/tie.ron");
            let knot = "phases[0].Tie.knot=Planned((file: \"../knots/fuzzed.ron\"))";
            let set = hagfish_scenario::Override::parse(knot).expect("a valid override");
            hagfish_fuzz::refused_run(&scenario, &[set]);
        }
    }
});
