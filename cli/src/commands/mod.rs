//! One file per command: its arguments, its help, and the printing of its
//! report.

pub mod budget;
pub mod depth;
pub mod eval;
pub mod faults;
pub mod rtl;
pub mod synth;
pub mod verilog;

/// Prints the notes of a loaded input on stderr.
fn print_notes(notes: &[String]) {
    for n in notes {
        eprintln!("note: {n}");
    }
}

/// `value` as one line of JSON on stdout.
fn print_json<T: serde::Serialize>(value: &T) {
    println!("{}", serde_json::to_string(value).expect("reports serialize"));
}

/// `--out`, or `./declivity-out/PREFIX-STEM` for the input `path`.
fn out_dir(out: &Option<std::path::PathBuf>, prefix: &str, path: &std::path::Path) -> std::path::PathBuf {
    out.clone().unwrap_or_else(|| {
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "image".into());
        std::path::PathBuf::from("declivity-out").join(format!("{prefix}-{stem}"))
    })
}
