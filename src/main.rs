//! The `layertrace` command-line tool.
fn main() {}
