//! Prints the diagnostics (and, with `-v`, the blocks) of the files given.
use stanok_syntax::{parse, Dialect};

fn main() {
    let mut verbose = false;
    for arg in std::env::args().skip(1) {
        if arg == "-v" {
            verbose = true;
            continue;
        }
        let text = match std::fs::read(&arg) {
            Ok(t) => String::from_utf8_lossy(&t).into_owned(),
            Err(e) => {
                eprintln!("{arg}: {e}");
                continue;
            }
        };
        let (program, diags) = parse(&text, Dialect::from_path(std::path::Path::new(&arg)));
        for d in &diags {
            println!("{arg}:{d}");
        }
        if verbose {
            for b in &program.blocks {
                println!("{:?}", b);
            }
        }
    }
}
