//! Cross-crate integration and statistical tests for hodr live in `tests/`.
//!
//! The README's code examples are compiled and run as doctests of this crate.

#[doc = include_str!("../../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
