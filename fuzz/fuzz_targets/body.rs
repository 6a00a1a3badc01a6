//! A body file, as `hagfish run data/scenarios/thesis.ron --body FILE` reads it.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let body = hagfish_fuzz::write("hagfish/fuzzed.ron", data);
    let scenario = hagfish_fuzz::scratch().join("scenarios/thesis.ron");
    if let Ok(body) = hagfish::runner::body_override(&body) {
        hagfish_fuzz::refused_run(&scenario, &[body]);
    }
});
