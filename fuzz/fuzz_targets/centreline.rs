//! A centreline CSV, as `hagfish knot FILE` reads it (and prints the knot of every frame).
#![no_main]

use clap::Parser;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let path = hagfish_fuzz::write("centreline.csv", data);
    let args = ["hagfish", "knot", path.to_str().expect("a UTF-8 scratch path")];
    if let Ok(cli) = hagfish::cli::Cli::try_parse_from(args) {
        drop(hagfish::cli::run(cli));
    }
});
