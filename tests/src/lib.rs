//! Cross-crate integration and statistical tests for hodr live in `tests/`.
