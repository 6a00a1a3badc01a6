//! A `--set PATH=VALUE` argument on `hagfish run data/scenarios/thesis.ron`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let scenario = hagfish_fuzz::scratch().join("scenarios/thesis.ron");
    if let Ok(set) = hagfish_scenario::Override::parse(&text) {
        hagfish_fuzz::refused_run(&scenario, &[set]);
    }
});
