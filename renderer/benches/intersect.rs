//! PLACEHOLDER (being written): criterion bench of every intersection method.
fn main() {}
