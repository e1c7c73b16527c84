//! A short soak: a seeded random opponent for 30 simulated seconds, every
//! invariant checked every tick.

#[test]
fn short_soak_holds_every_invariant() {
    let r = shisen::tools::soak::soak(0.5, 7, (false, None), |_| true);
    println!(
        "soak 30 s: {} events, {} VH punches, {} head-contact ticks, {} resets, worst excursion {:.2} deg, rss {:?} KiB",
        r.events, r.vh_punches, r.head_hit_ticks, r.resets, r.worst_limit_excess_deg, r.rss_kib
    );
    assert!(r.passed(), "{:?}", r.failures);
    assert!(r.events > 20, "the opponent was active");
    assert_eq!(r.resets, 0, "no blow-ups with the shipped gains");
}
