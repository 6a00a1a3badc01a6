//! A scenario file, as `hagfish run FILE` reads it (its body, `data/hagfish/es103.ron`, at
//! `../hagfish/es103.ron` as in the shipped scenarios).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let path = hagfish_fuzz::write("scenarios/fuzzed.ron", data);
    hagfish_fuzz::refused_run(&path, &[]);
});
