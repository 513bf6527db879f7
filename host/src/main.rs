//! The `hodr` command line.

fn main() {}
