//! viewer
fn main() {}
