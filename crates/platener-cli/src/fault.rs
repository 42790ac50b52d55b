//! Fault injection for the command-line tests: `PLATENER_FAULT=METHOD=KIND[,METHOD=KIND]`
//! makes a method fail (`error`), panic (`panic`) or run until cancelled (`hang`), so tests
//! can show that the batch survives each, whatever the methods do by then. The library does
//! the failing ([`platener::convert::Fault`]); this only reads the variable. Not for users.

use platener::convert::{Fault, FaultKind};

/// The environment variable read.
pub const VARIABLE: &str = "PLATENER_FAULT";

/// The faults `PLATENER_FAULT` asks for (none when it is unset); unknown words are ignored.
pub fn from_env() -> Vec<Fault> {
    let Ok(spec) = std::env::var(VARIABLE) else {
        return Vec::new();
    };
    spec.split(',')
        .filter_map(|rule| {
            let (name, kind) = rule.split_once('=')?;
            let method = name.trim().parse().ok()?;
            let kind = match kind.trim() {
                "error" => FaultKind::Error,
                "panic" => FaultKind::Panic,
                "hang" => FaultKind::Hang,
                _ => return None,
            };
            Some(Fault { method, kind })
        })
        .collect()
}
