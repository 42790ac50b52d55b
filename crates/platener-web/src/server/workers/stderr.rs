//! A worker's standard error, copied line by line to the server's, watched for the one sign
//! of running out of memory a process leaves: under the address-space limit an allocation
//! fails, and Rust's allocator prints `memory allocation of N bytes failed` and aborts. The
//! exit status alone (SIGABRT) cannot tell that from any other abort.

use std::io::Write as _;

use tokio::io::{AsyncBufReadExt as _, AsyncReadExt as _, BufReader};
use tokio::process::ChildStderr;

/// Lines are copied in pieces of at most this many bytes, so a line without an end cannot
/// grow the server's memory.
const MAX_LINE: u64 = 16 * 1024;

/// Whether a line of a worker's standard error is the allocator's out-of-memory message.
pub fn says_out_of_memory(line: &[u8]) -> bool {
    let line = String::from_utf8_lossy(line);
    line.contains("memory allocation of ") && line.contains(" failed")
}

/// Copies `stderr` to the server's standard error until it ends (the worker exited); whether
/// it reported an allocation failure.
pub async fn forward(stderr: ChildStderr) -> bool {
    let mut reader = BufReader::new(stderr);
    let mut line = Vec::new();
    let mut out_of_memory = false;
    loop {
        line.clear();
        match (&mut reader).take(MAX_LINE).read_until(b'\n', &mut line).await {
            Ok(0) | Err(_) => return out_of_memory,
            Ok(_) => {
                out_of_memory |= says_out_of_memory(&line);
                let _ = std::io::stderr().lock().write_all(&line);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_allocators_message_is_recognised() {
        assert!(says_out_of_memory(b"memory allocation of 67108864 bytes failed\n"));
        assert!(!says_out_of_memory(b"INFO worker started\n"));
    }
}
