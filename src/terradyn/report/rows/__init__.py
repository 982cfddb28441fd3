"""The rows of the thesis reproduction report, one module per thesis chapter, and the table naming them.

A *row* is one model's computation for one thesis item: a function ``name(quick) -> ItemOutput``
(:class:`terradyn.report.registry.ItemOutput`). :data:`ROWS` maps (item key, model) to the row's
``"module:function"``; the registry imports a row's module only when the row runs, and nothing here
registers itself on import. A row that one computation covers for two models (RFT and Wong-Reece share
one sweep, RFT and DRFT one high-speed sweep) is listed under the first model; the other points to it
as ``"=first"``. Rows of users' own code plug in with :func:`terradyn.report.register_row`.

Modules: :mod:`.ch3`, :mod:`.ch4`, :mod:`.ch6`, :mod:`.ch7_8`, :mod:`.ch9_footing` (Fig. 9-1),
:mod:`.ch9_intrusion` (packing, wedges, superposition), :mod:`.ch9_drag` (plowing, lift and drag,
Fig. 9-9), and :mod:`.common` (what several of them share).
"""

from __future__ import annotations

__all__ = ["ROWS"]

#: (item key, model) -> "module:function" of the row, or "=model" for a row another model's row covers
ROWS: dict[tuple[str, str], str] = {
    # chapter 3
    ("ch3-pressure-sinkage", "bekker"): "terradyn.report.rows.ch3:pressure_sinkage_bekker",
    ("ch3-pressure-sinkage", "rft"): "=bekker",
    # chapter 4
    ("fig-4-1", "rft"): "terradyn.report.rows.ch4:alpha_map_rft",
    ("fig-4-1", "mpm"): "terradyn.report.rows.ch4:alpha_map_mpm",
    ("fig-4-1", "dem"): "terradyn.report.rows.ch4:alpha_map_dem",
    ("ch4-plate-depth", "rft"): "terradyn.report.rows.ch4:plate_depth_rft",
    ("ch4-plate-depth", "mpm"): "terradyn.report.rows.ch4:plate_depth_mpm",
    ("ch4-plate-depth", "dem"): "terradyn.report.rows.ch4:plate_depth_dem",
    # chapter 6
    ("tab-6-1", "bekker"): "terradyn.report.rows.ch6:material_audit_bekker",
    ("tab-6-1", "rft"): "=bekker",
    ("tab-6-2", "theory"): "terradyn.report.rows.ch6:wheels_table_theory",
    ("fig-6-8", "rft"): "terradyn.report.rows.ch6:wheel_a_force_slip_rft",
    ("fig-6-8", "wong-reece"): "=rft",
    ("fig-6-8", "mpm"): "terradyn.report.rows.ch6:wheel_a_force_slip_mpm",
    ("ch6-wheels-bc", "rft"): "terradyn.report.rows.ch6:wheels_bc_force_slip_rft",
    ("ch6-wheels-bc", "wong-reece"): "=rft",
    ("ch6-wheels-bc", "mpm"): "terradyn.report.rows.ch6:wheels_bc_force_slip_mpm",
    ("ch6-flapped", "rft"): "terradyn.report.rows.ch6:flapped_rft",
    ("ch6-flapped", "mpm"): "terradyn.report.rows.ch6:flapped_mpm",
    # chapters 7 and 8
    ("ch7-optimisation", "rft"): "terradyn.report.rows.ch7_8:optimisation_rft",
    ("ch8-high-speed", "rft"): "=drft",
    ("ch8-high-speed", "drft"): "terradyn.report.rows.ch7_8:high_speed_drft",
    ("ch8-high-speed", "mpm"): "terradyn.report.rows.ch7_8:high_speed_mpm",
    ("ch8-onset-criterion", "drft"): "terradyn.report.rows.ch7_8:onset_criterion_drft",
    # chapter 9
    ("fig-9-1", "theory"): "terradyn.report.rows.ch9_footing:slip_lines_theory",
    ("fig-9-1", "mpm"): "terradyn.report.rows.ch9_footing:footing_mpm",
    ("ch9-plate-packing", "mpm"): "terradyn.report.rows.ch9_intrusion:plate_packing_mpm",
    ("ch9-plate-packing", "dem"): "terradyn.report.rows.ch9_intrusion:plate_packing_dem",
    ("ch9-wedges", "rft"): "terradyn.report.rows.ch9_intrusion:wedges_rft",
    ("ch9-wedges", "mpm"): "terradyn.report.rows.ch9_intrusion:wedges_mpm",
    ("ch9-superposition", "rft"): "terradyn.report.rows.ch9_intrusion:superposition_rft",
    ("ch9-superposition", "mpm"): "terradyn.report.rows.ch9_intrusion:superposition_mpm",
    ("ch9-plowing", "mpm"): "terradyn.report.rows.ch9_drag:plowing_mpm",
    ("ch9-plowing", "dem"): "terradyn.report.rows.ch9_drag:plowing_dem",
    ("ch9-lift-drag", "rft"): "terradyn.report.rows.ch9_drag:lift_drag_rft",
    ("ch9-lift-drag", "mpm"): "terradyn.report.rows.ch9_drag:lift_drag_mpm",
    ("fig-9-9", "mpm"): "terradyn.report.rows.ch9_drag:cylinder_fields_mpm",
}
