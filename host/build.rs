//! Records the commit this binary is built from, for the suite's header: `HODR_COMMIT` is
//! `git rev-parse --short HEAD` of the checkout, with " + uncommitted changes" when a
//! tracked file of the crates compiled into the binary (or the workspace's manifest and
//! lock file) differs from it, and empty outside a git checkout or without git.
//!
//! Read at build time rather than when the binary runs, so that a binary copied aside or
//! run after the checkout has moved on still names the code it was built from. The script
//! reruns when HEAD, the index or a branch moves, or a file under those crates changes.

use std::path::Path;
use std::process::Command;

/// The crates and files whose state the stamp describes, relative to the workspace root.
const SOURCES: [&str; 5] = ["core", "raster", "host", "Cargo.toml", "Cargo.lock"];

fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .arg("-C")
        .arg(dir)
        .args(args)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn main() {
    let manifest = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
    let host = Path::new(&manifest);
    let root = host.parent().unwrap_or(host);
    for source in SOURCES {
        println!("cargo:rerun-if-changed={}", root.join(source).display());
    }
    let Some(head) = git(host, &["rev-parse", "--short", "HEAD"]) else {
        println!("cargo:rustc-env=HODR_COMMIT=");
        return;
    };
    for file in ["HEAD", "index", "packed-refs", "refs/heads"] {
        if let Some(path) = git(host, &["rev-parse", "--git-path", file]) {
            // --git-path answers relative to the directory git ran in.
            println!("cargo:rerun-if-changed={}", host.join(path).display());
        }
    }
    let mut status = vec!["status", "--porcelain", "--untracked-files=no", "--"];
    let pathspecs: Vec<String> = SOURCES.iter().map(|s| format!(":/{s}")).collect();
    status.extend(pathspecs.iter().map(String::as_str));
    let dirty = git(host, &status).is_some_and(|s| !s.is_empty());
    let stamp = if dirty {
        format!("{head} + uncommitted changes")
    } else {
        head
    };
    println!("cargo:rustc-env=HODR_COMMIT={stamp}");
}
