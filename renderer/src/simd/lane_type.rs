//! Which lane type runs: the widest this CPU has, or a narrower one named
//! by the `RAYLAB_LANES` environment variable (to measure or test the
//! fallbacks on a machine that has more).

use super::{Portable, WithLanes};
use std::sync::OnceLock;

/// The environment variable that names a narrower lane type than the
/// widest this CPU has: `portable`, `avx2` or `avx512`.
pub const LANES_VARIABLE: &str = "RAYLAB_LANES";

/// One of the [`super::FloatLanes`] implementations, narrowest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum LaneType {
    /// [`Portable`]: `wide`, whatever the build targets.
    Portable,
    /// [`super::avx2::Avx2`]: two AVX registers.
    Avx2,
    /// [`super::avx512::Avx512`]: one AVX-512 register.
    Avx512,
}

impl LaneType {
    /// Every lane type, narrowest first.
    pub const ALL: [LaneType; 3] = [LaneType::Portable, LaneType::Avx2, LaneType::Avx512];

    /// The name `RAYLAB_LANES` takes and reports print.
    pub fn name(self) -> &'static str {
        match self {
            LaneType::Portable => "portable",
            LaneType::Avx2 => "avx2",
            LaneType::Avx512 => "avx512",
        }
    }

    /// The lane type called `name` (as [`LaneType::name`] spells it).
    pub fn from_name(name: &str) -> Option<LaneType> {
        Self::ALL.into_iter().find(|lanes| lanes.name() == name)
    }

    /// Whether this CPU can run it.
    pub fn is_available(self) -> bool {
        match self {
            LaneType::Portable => true,
            #[cfg(target_arch = "x86_64")]
            LaneType::Avx2 => super::avx2::Avx2Token::detect().is_some(),
            #[cfg(target_arch = "x86_64")]
            LaneType::Avx512 => super::avx512::Avx512Token::detect().is_some(),
            #[cfg(not(target_arch = "x86_64"))]
            LaneType::Avx2 | LaneType::Avx512 => false,
        }
    }

    /// The lane types this CPU can run, narrowest first.
    pub fn available() -> Vec<LaneType> {
        Self::ALL.into_iter().filter(|l| l.is_available()).collect()
    }

    /// The widest lane type this CPU can run.
    pub fn widest() -> LaneType {
        Self::ALL
            .into_iter()
            .rev()
            .find(|l| l.is_available())
            .unwrap_or(LaneType::Portable)
    }

    /// The lane type [`super::dispatch`] runs, decided once per process:
    /// the widest this CPU has, or the one `RAYLAB_LANES` names when this
    /// CPU has it ([`LaneType::requested`] says when it cannot be used).
    pub fn chosen() -> LaneType {
        static CHOSEN: OnceLock<LaneType> = OnceLock::new();
        *CHOSEN.get_or_init(|| match Self::requested() {
            Ok(Some(lanes)) => lanes,
            Ok(None) | Err(_) => Self::widest(),
        })
    }

    /// The lane type `RAYLAB_LANES` asks for: none when it is unset or
    /// empty; an error saying why when it names no lane type or one this
    /// CPU does not have.
    pub fn requested() -> Result<Option<LaneType>, String> {
        let Ok(value) = std::env::var(LANES_VARIABLE) else {
            return Ok(None);
        };
        Self::parse_request(&value)
    }

    /// [`LaneType::requested`] for the variable's value `value`.
    fn parse_request(value: &str) -> Result<Option<LaneType>, String> {
        let value = value.trim();
        if value.is_empty() {
            return Ok(None);
        }
        let names = Self::ALL.map(LaneType::name).join(", ");
        let widest = Self::widest().name();
        let lanes = Self::from_name(value).ok_or_else(|| {
            format!(
                "{LANES_VARIABLE}={value:?} names no lane type (one of: {names}); using {widest}"
            )
        })?;
        if !lanes.is_available() {
            return Err(format!(
                "{LANES_VARIABLE}={value:?}: this CPU cannot run {value} lanes; \
                 using {widest}"
            ));
        }
        Ok(Some(lanes))
    }

    /// Runs `job` with these lanes, or with [`Portable`] ones if this CPU
    /// does not have them.
    #[inline]
    pub fn run<W: WithLanes>(self, job: W) -> W::Output {
        #[cfg(target_arch = "x86_64")]
        match self {
            LaneType::Avx512 => {
                if let Some(token) = super::avx512::Avx512Token::detect() {
                    return token.run(job);
                }
            }
            LaneType::Avx2 => {
                if let Some(token) = super::avx2::Avx2Token::detect() {
                    return token.run(job);
                }
            }
            LaneType::Portable => {}
        }
        job.run::<Portable>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_or_missing_lanes_are_errors_that_say_why() {
        for lanes in LaneType::ALL {
            assert_eq!(LaneType::from_name(lanes.name()), Some(lanes));
        }
        assert_eq!(LaneType::parse_request(""), Ok(None));
        assert_eq!(
            LaneType::parse_request(" portable "),
            Ok(Some(LaneType::Portable))
        );
        let error = LaneType::parse_request("avx9").expect_err("no such lane type");
        assert!(
            error.contains("RAYLAB_LANES") && error.contains("avx512"),
            "{error}"
        );
        for lanes in LaneType::ALL {
            let request = LaneType::parse_request(lanes.name());
            assert_eq!(request.is_ok(), lanes.is_available(), "{request:?}");
        }
    }

    #[test]
    fn the_widest_lane_type_is_the_widest_this_cpu_has() {
        let available = LaneType::available();
        assert_eq!(available[0], LaneType::Portable);
        assert_eq!(available.last(), Some(&LaneType::widest()));
        #[cfg(target_arch = "x86_64")]
        {
            assert_eq!(
                LaneType::Avx2.is_available(),
                is_x86_feature_detected!("avx2")
            );
            assert_eq!(
                LaneType::Avx512.is_available(),
                is_x86_feature_detected!("avx512f")
                    && is_x86_feature_detected!("avx512bw")
                    && is_x86_feature_detected!("avx512dq")
            );
        }
    }
}
