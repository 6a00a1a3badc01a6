//! Records the platform the regression runner was built for (target triple and rustc
//! version): a golden's bitwise digest is only compared on the platform it was blessed on.

use std::process::Command;

fn main() {
    let target = std::env::var("TARGET").unwrap_or_else(|_| "unknown".into());
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = Command::new(rustc)
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map_or_else(|| "unknown".into(), |v| v.trim().to_owned());
    println!("cargo:rustc-env=XTASK_TARGET={target}");
    println!("cargo:rustc-env=XTASK_RUSTC={version}");
    println!("cargo:rerun-if-env-changed=RUSTC");
}
