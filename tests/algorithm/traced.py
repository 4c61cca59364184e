"""Settings that traced scenario tests pin, so that a later change of a default does not
move their seeds off the situation they were written for."""

from etswarm.sim.params import SimParams

#: Until session 73 a first formation's searcher plunged in a notch's mouth only on a
#: ring, and never pressed; first formations traced before then run as described with
#: this.
SESSION_72_FORMATION = {"late_plunge_s": 0.0}

#: Until session 70 every plunge edge-followed the placed robots 35 mm away, a body and
#: 2 mm; regrowths traced before then plunge as described with this.
SESSION_69_REGROWTH = {"regrowth_plunge_aim_mm": 35.0, **SESSION_72_FORMATION}

#: Until session 62 a status carried no bits of its sender's target, and a sibling
#: remnant's robot was foreign to a searcher only by its tag or its held-sites message;
#: regrowths traced before then run as described with this.
#: Until session 65 a shape with a hole grew with no wave at all (a searcher took the
#: first free site it could locate), and a searcher did not say when it placed itself in
#: the hole; first formations of `O` traced before then form as described with this.
#: Until session 66 every placed robot a searcher heard after damage took part in its
#: consistency check, even one the lattice puts out of radio range of the candidate site
#: whose reading fits the pair's other site no better; regrowths traced before then run
#: as described with this (first formations are unchanged).
SESSION_65_REGROWTH = {"regrowth_fold_skip_mm": 0.0, **SESSION_69_REGROWTH}

SESSION_64_FORMATION = {"rim_wave_s": 0.0, "inside_bit": "off", **SESSION_65_REGROWTH}

SESSION_61_REGROWTH = {"status_signature": "off", **SESSION_64_FORMATION}

#: Until session 59 a searcher that came to a pair from a robot outside it took the one
#: it steered by for the one it passed first, after damage too (``met_order``);
#: regrowths traced before then run as described with this.
SESSION_59_REGROWTH = {"came_order": "off", **SESSION_61_REGROWTH}

#: Until session 59 a searcher edge-followed a robot parked by a too-small remnant as any
#: Queued robot, a placed robot beside one did not elect again with it, and a robot kept on
#: its site by a regeneration kept it with no kept neighbour site; regrowths traced before
#: then run as described with this.
SESSION_58_REGROWTH = {
    "parked_obstacle": "off", "merge_parked": "off", "lone_kept_leave": "off",
    **SESSION_59_REGROWTH,
}

#: Until session 58 a searcher kept 38 mm (not 34) from other searchers, Queued robots and
#: robots of another shape; runs traced before then run as described with this.
SESSION_57_SEARCH = {"clearance_mm": 38.0, **SESSION_58_REGROWTH}

#: Until session 57 a searcher that flipped back to the robot it came from, after steering
#: by the other of a pair for 2 s, took that other robot for the one it came from, and a
#: third robot ruled a pair's mirror site out by the consistency tolerance alone; first
#: formations and regrowths traced before then run as described with this.
SESSION_56_SEARCH = {"from_return_s": 0.0, "mirror_margin_mm": 0.0, **SESSION_57_SEARCH}

#: Until session 48 a searcher plunged (edge-followed nearer the placed robots) only after
#: damage; first formations traced before then form as described with this.
SESSION_47_FORMATION = {"first_plunge_after_s": 0.0, **SESSION_56_SEARCH}

#: Until session 45 a searcher took the first free site it could locate, the waves from
#: the seeds were an option; first formations traced before then form as described with
#: this (and so do the shapes their damage then cuts).
SESSION_44_FORMATION = {"wave_s": 0.0, **SESSION_47_FORMATION}

#: Until session 35 a thin shape (cells at most two steps from its outside) formed with
#: the compact shapes' settle retries and release clear time; first formations of `T`,
#: triangle, `L`, `E`, `H` and arrow traced before then form as described with this.
SESSION_34_FORMATION = {"thin_depth": 0, **SESSION_44_FORMATION}

#: Until session 27 a searcher got the wide window only at sites of three or more placed
#: neighbours, in the first formation too; shapes traced before then are formed as
#: described with this.
SESSION_26_FORMATION = {"two_neighbour_widen_s": 0.0, **SESSION_34_FORMATION}

#: Until session 20 a searcher's windows widened over 1200 s at the shape and it refused
#: at most two pinching captures; seeds traced before then stall or form as described
#: with these.
SESSION_19_WIDENING = {"widen_s": 1200.0, "capture_pinch_refusals": 2, **SESSION_26_FORMATION}

#: Until session 56 a searcher long at a regrowing shape plunged only after a failed
#: confirmation, not in a notch's mouth; regrowths traced before then run as described
#: with this.
SESSION_55_REGROWTH = {"mouth_plunge": "off", **SESSION_56_SEARCH}

#: Until session 55 a searcher released where a regenerated target left it out did not
#: know it stood by its former site, and took sites across a pair from it; regrowths
#: traced before then run as described with this.
SESSION_54_REGROWTH = {"former_site_slack_mm": 0.0, **SESSION_55_REGROWTH}

#: Until session 54 a searcher of a regenerated target got the wide window only at sites
#: of three or more placed neighbours, however long it had been at the shape; regrowths
#: traced before then run as described with this.
SESSION_53_REGROWTH = {"regrowth_two_neighbour_widen_s": 0.0, **SESSION_54_REGROWTH}

#: Until session 50 a lost searcher pivoted straight back into a sibling remnant's robots,
#: and only a robot whose tag is no site of the searcher's target was foreign to it;
#: regrowths traced before then run as described with this.
SESSION_49_REGROWTH = {"lost_escape_s": 0.0, "signed_foreign": "off", **SESSION_53_REGROWTH}

#: Until session 34 a Leader kept the scaled shape in the original's orientation;
#: regrowths traced before then place and branch as described with this.
SESSION_33_PLACEMENT = {"placement_turns": "off", **SESSION_49_REGROWTH}

#: Until session 32 a Leader's placement counted cells off the old shape like any other;
#: regrowths traced before then place and branch as described with this.
SESSION_31_PLACEMENT = {"placement_off_shape": "any", **SESSION_33_PLACEMENT}

#: Until session 69 a first-formation searcher went round its piece of a broken queue for
#: good; runs traced before then whose queue broke run as described with this.
SESSION_68_QUEUE = {"repository_gap_s": 0.0}

#: Until session 53 every run computed its sines, cosines, arctangents, logarithms and
#: normal draws with the platform's maths library (``portable_math`` off). Seeds traced
#: before then run as described with this, on x86-64 machines whose glibc picks its FMA
#: code, as the machines they were traced on and CI's did.
NATIVE_MATHS = SimParams(portable_math=False)
