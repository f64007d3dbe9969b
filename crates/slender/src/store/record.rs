//! One stored case: the file format of the result store.
//!
//! A record file is TOML (exact for every f64, NaN and ±∞ included, unlike JSON) behind a
//! header line that carries the SHA-256 of the body:
//!
//! ```text
//! # slender record sha256=<64 hex digits>
//! benchmark = "cantilever"
//! code_version = "0.1.0+src.1a2b3c4d5e6f"
//! seconds = 0.0123
//! [params]   # everything the result depends on
//! [record]   # the result
//! ```
//!
//! A file whose body does not match its checksum, does not parse, or belongs to other
//! parameters or another code version is *not* a record: the case is computed again.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

const HEADER: &str = "# slender record sha256=";

/// The code version records are keyed by (see build.rs).
pub const CODE_VERSION: &str = env!("SLENDER_CODE_VERSION");

/// Hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The body of a record file.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Envelope<P, R> {
    /// Benchmark name (the store's subdirectory).
    pub benchmark: String,
    /// [`CODE_VERSION`] of the code that computed it.
    pub code_version: String,
    /// Wall time of the computation (s). Not part of the result: it varies between runs.
    pub seconds: f64,
    /// Every parameter the result depends on.
    pub params: P,
    /// The result.
    pub record: R,
}

/// Why a file is not a usable record.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum RecordError {
    /// No header line, or a header without a checksum.
    #[error("missing header line `{HEADER}…`")]
    NoHeader,
    /// The body does not hash to the header's checksum (a torn or edited file).
    #[error("checksum mismatch (torn or edited file)")]
    Checksum,
    /// The body is not a record of the expected shape.
    #[error("unreadable body: {0}")]
    Parse(String),
    /// A record of another benchmark, code version or parameter set.
    #[error("record of other parameters or another code version")]
    Mismatch,
}

/// Serializes an envelope as a record file.
pub fn encode<P: Serialize, R: Serialize>(env: &Envelope<P, R>) -> Result<String, RecordError> {
    let body = toml::to_string(env).map_err(|e| RecordError::Parse(e.to_string()))?;
    Ok(format!("{HEADER}{}\n{body}", sha256_hex(body.as_bytes())))
}

/// Checks the header and returns the body.
fn verified_body(text: &str) -> Result<&str, RecordError> {
    let (header, body) = text.split_once('\n').ok_or(RecordError::NoHeader)?;
    let sum = header.strip_prefix(HEADER).ok_or(RecordError::NoHeader)?;
    if sum.len() != 64 || sha256_hex(body.as_bytes()) != sum {
        return Err(RecordError::Checksum);
    }
    Ok(body)
}

/// Parses a record file without knowing its types (for `slender merge`).
pub fn decode_any(text: &str) -> Result<Envelope<toml::Value, toml::Value>, RecordError> {
    toml::from_str(verified_body(text)?).map_err(|e| RecordError::Parse(e.to_string()))
}

/// Parses a record file and checks that it belongs to `benchmark`, [`CODE_VERSION`] and
/// `params`; returns the record and its wall time.
pub fn decode<P: Serialize, R: DeserializeOwned>(
    text: &str,
    benchmark: &str,
    params: &P,
) -> Result<(R, f64), RecordError> {
    let env: Envelope<toml::Value, R> =
        toml::from_str(verified_body(text)?).map_err(|e| RecordError::Parse(e.to_string()))?;
    let expected = toml::Value::try_from(params).map_err(|e| RecordError::Parse(e.to_string()))?;
    if env.benchmark != benchmark || env.code_version != CODE_VERSION || env.params != expected {
        return Err(RecordError::Mismatch);
    }
    Ok((env.record, env.seconds))
}

/// The store key of a case: a hash of the benchmark, the code version and the parameters.
pub fn key<P: Serialize>(benchmark: &str, params: &P) -> Result<String, RecordError> {
    let p = toml::to_string(params).map_err(|e| RecordError::Parse(e.to_string()))?;
    let text = format!("{benchmark}\n{CODE_VERSION}\n{p}");
    Ok(sha256_hex(text.as_bytes())[..32].to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Serialize, Deserialize, PartialEq)]
    struct P {
        gamma: f64,
        n: usize,
    }

    #[derive(Debug, Serialize, Deserialize, PartialEq)]
    struct R {
        ratio: f64,
        lambda: Option<f64>,
        ok: bool,
    }

    fn sample() -> (P, R) {
        (
            P { gamma: 0.1, n: 20 },
            R {
                ratio: f64::NAN,
                lambda: Some(-1.0e-300),
                ok: false,
            },
        )
    }

    fn env<'a>(p: &'a P, r: &'a R) -> Envelope<&'a P, &'a R> {
        Envelope {
            benchmark: "cantilever".into(),
            code_version: CODE_VERSION.into(),
            seconds: 0.5,
            params: p,
            record: r,
        }
    }

    #[test]
    fn round_trip_is_exact_even_for_nan_and_subnormal_scales() {
        let (p, r) = sample();
        let text = encode(&env(&p, &r)).unwrap();
        let (back, secs): (R, f64) = decode(&text, "cantilever", &p).unwrap();
        assert!(back.ratio.is_nan());
        assert_eq!(back.lambda, r.lambda);
        assert_eq!(secs, 0.5);
        // Awkward decimal values survive bit for bit.
        for x in [0.1 + 0.2, 1.0 / 3.0, 6.02214076e23, -0.0, f64::MIN_POSITIVE] {
            let r = R {
                ratio: x,
                lambda: None,
                ok: true,
            };
            let text = encode(&env(&p, &r)).unwrap();
            let (back, _): (R, f64) = decode(&text, "cantilever", &p).unwrap();
            assert_eq!(back.ratio.to_bits(), x.to_bits());
            assert_eq!(back.lambda, None);
        }
    }

    #[test]
    fn torn_edited_and_foreign_records_are_rejected() {
        let (p, r) = sample();
        let text = encode(&env(&p, &r)).unwrap();
        let torn = &text[..text.len() - 5];
        assert_eq!(
            decode::<P, R>(torn, "cantilever", &p).unwrap_err(),
            RecordError::Checksum
        );
        let edited = text.replace("ok = false", "ok = true");
        assert_ne!(edited, text);
        assert_eq!(
            decode::<P, R>(&edited, "cantilever", &p).unwrap_err(),
            RecordError::Checksum
        );
        assert_eq!(
            decode::<P, R>("", "cantilever", &p).unwrap_err(),
            RecordError::NoHeader
        );
        let other = P { gamma: 0.2, n: 20 };
        assert_eq!(
            decode::<P, R>(&text, "cantilever", &other).unwrap_err(),
            RecordError::Mismatch
        );
        assert_eq!(
            decode::<P, R>(&text, "bend-twist", &p).unwrap_err(),
            RecordError::Mismatch
        );
    }

    #[test]
    fn keys_separate_parameters_and_benchmarks() {
        let a = key("cantilever", &P { gamma: 0.1, n: 20 }).unwrap();
        let b = key("cantilever", &P { gamma: 0.1, n: 21 }).unwrap();
        let c = key("bend-twist", &P { gamma: 0.1, n: 20 }).unwrap();
        assert_eq!(a.len(), 32);
        assert!(a != b && a != c && b != c);
        assert_eq!(a, key("cantilever", &P { gamma: 0.1, n: 20 }).unwrap());
    }
}
