//! Fault injection for the command-line tests: `PLATENER_FAULT=METHOD=KIND[,METHOD=KIND]`
//! makes a method fail (`error`), panic (`panic`) or run until cancelled (`hang`), so tests
//! can show that the batch survives each, whatever the methods do by then. Not for users;
//! unset, it costs one environment lookup per method.

use platener::Cancel;
use platener::method::MethodKind;

/// The environment variable read.
pub const VARIABLE: &str = "PLATENER_FAULT";

/// Fails, panics or hangs as `PLATENER_FAULT` asks for `method`; does nothing otherwise.
pub fn inject(method: MethodKind, cancel: &Cancel) -> Result<(), String> {
    let Ok(spec) = std::env::var(VARIABLE) else {
        return Ok(());
    };
    for rule in spec.split(',') {
        let Some((name, kind)) = rule.split_once('=') else {
            continue;
        };
        if name.trim() != method.name() {
            continue;
        }
        match kind.trim() {
            "error" => return Err(format!("{VARIABLE} asked the {} method to fail", method.name())),
            "panic" => panic!("{VARIABLE} asked the {} method to panic", method.name()),
            "hang" => {
                while !cancel.is_cancelled() {
                    std::thread::sleep(std::time::Duration::from_millis(5));
                }
                return Err("cancelled".into());
            }
            _ => {}
        }
    }
    Ok(())
}
