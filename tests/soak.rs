//! A short soak: a seeded random opponent for 30 simulated seconds, every
//! invariant checked every tick.

#[test]
fn short_soak_holds_every_invariant() {
    let r = shisen::tools::soak::soak(0.5, 7, Default::default(), |_| true);
    println!(
        "soak 30 s: {} events, {} VH punches, {} head-contact ticks, {} resets, worst excursion {:.2} deg, rss {:?} KiB",
        r.events, r.vh_punches, r.head_hit_ticks, r.resets, r.worst_limit_excess_deg, r.rss_kib
    );
    assert!(r.passed(), "{:?}", r.failures);
    assert!(r.events > 20, "the opponent was active");
    assert_eq!(r.resets, 0, "no blow-ups with the shipped gains");
}

/// In rounds the soak is a bout: three minutes fought, a minute's rest in
/// which the partner throws nothing, and the next round.
#[test]
fn a_soak_in_rounds_rests_between_them() {
    use shisen::tools::soak::{BotRates, SoakSetup, soak};
    // A partner pressing hard (0.8 punches a second), so punches thrown in
    // the rest would show.
    let setup = SoakSetup {
        rounds: true,
        partner: BotRates {
            punch: 0.8,
            ..Default::default()
        },
        ..Default::default()
    };
    // 3 min of round 1, the minute's rest, 20 s of round 2.
    let r = soak(4.0 + 20.0 / 60.0, 7, setup, |_| true);
    assert!(r.passed(), "{:?}", r.failures);
    let fought: u32 = r.card.at_range.iter().sum();
    assert_eq!(fought, 200_000, "ticks fought");
    // The partner's punches all fell in the 200 s fought (about 0.8 a
    // second), none in the rest.
    let thrown = r.card.you.total().thrown;
    // (Punching through the rest too would make it about 210.)
    assert!((120..190).contains(&thrown), "{thrown} punches");
}

/// The partner defends as a sparring partner does (covering up and
/// slipping after a human reaction time, besides the guard it keeps): a
/// pro's punches land less often on it than on one that only keeps its
/// guard, and about as often as elite boxers' do (28-40 %; Davis et al.
/// 2018). Three seeds pooled: one two-minute bout varies by about ten
/// points.
#[test]
fn the_partner_defends_against_the_vh_punches() {
    use shisen::tools::soak::{BotRates, SoakSetup, soak};
    let accuracy = |defend: f64| {
        let (mut landed, mut thrown) = (0, 0);
        for seed in 1..=3 {
            let setup = SoakSetup {
                opponent: Some("pro".parse().expect("a level")),
                partner: BotRates {
                    defend,
                    ..Default::default()
                },
                ..Default::default()
            };
            let r = soak(2.0, seed, setup, |_| true);
            assert!(r.passed(), "{:?}", r.failures);
            let vh = r.card.vh.total();
            (landed, thrown) = (landed + vh.landed, thrown + vh.thrown);
        }
        assert!(thrown > 90, "{thrown} punches");
        f64::from(landed) / f64::from(thrown)
    };
    let (guarded, defended) = (accuracy(0.0), accuracy(0.6));
    println!(
        "the pro's accuracy: {guarded:.2} on a partner that only keeps its guard, {defended:.2} on one that defends"
    );
    assert!(defended < guarded - 0.05, "{defended} against {guarded}");
    assert!((0.2..0.45).contains(&defended), "{defended}");
}
