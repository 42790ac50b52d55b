//! Random ids and delete tokens, and the hash under which tokens are stored.
//!
//! Ids are 128 random bits so a private conversion cannot be found by guessing; tokens are
//! 256 bits and only their SHA-256 is stored, so a copy of the database cannot delete or
//! publish anything.

use sha2::{Digest, Sha256};

/// Lower-case hex of `bytes`.
fn hex(bytes: &[u8]) -> String {
    const DIGITS: &[u8; 16] = b"0123456789abcdef";
    let mut s = String::with_capacity(bytes.len() * 2);
    for b in bytes {
        s.push(char::from(DIGITS[usize::from(b >> 4)]));
        s.push(char::from(DIGITS[usize::from(b & 15)]));
    }
    s
}

/// `n` bytes from the operating system's random source.
fn random<const N: usize>() -> [u8; N] {
    let mut bytes = [0u8; N];
    // The OS source fails only on a broken system; then no id is better than a guessable one.
    getrandom::fill(&mut bytes).expect("the operating system's random source works");
    bytes
}

/// A new conversion id: `c_` and 128 random bits in hex.
pub fn conversion_id() -> String {
    format!("c_{}", hex(&random::<16>()))
}

/// A new delete token: 256 random bits in hex.
pub fn token() -> String {
    hex(&random::<32>())
}

/// The stored form of a token: its SHA-256 in hex.
pub fn hash_token(token: &str) -> String {
    hex(&Sha256::digest(token.as_bytes()))
}

/// Whether `id` has the shape of a conversion id; anything else is answered 404 without
/// touching the database.
pub fn is_conversion_id(id: &str) -> bool {
    id.len() == 34 && id.starts_with("c_") && id[2..].bytes().all(|b| b.is_ascii_hexdigit())
}

/// Compares two strings in time independent of where they differ.
pub fn same(a: &str, b: &str) -> bool {
    a.len() == b.len() && a.bytes().zip(b.bytes()).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_random_and_well_formed() {
        let a = conversion_id();
        let b = conversion_id();
        assert_ne!(a, b);
        assert!(is_conversion_id(&a), "{a}");
        assert!(!is_conversion_id("c_../../etc/passwd"));
        assert_eq!(token().len(), 64);
    }

    #[test]
    fn tokens_are_stored_hashed() {
        let t = token();
        let h = hash_token(&t);
        assert_ne!(h, t);
        assert!(same(&h, &hash_token(&t)));
        assert!(!same(&h, &hash_token("other")));
        // SHA-256 of "abc", a published test vector.
        assert_eq!(
            hash_token("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }
}
