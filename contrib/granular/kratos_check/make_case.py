#!/usr/bin/env python3
"""Write a Kratos MPM (10.4.x) input for the Bui et al. 2008 granular column
collapse: 0.2 m x 0.1 m column against a wall at x = 0 on a floor y = 0.

Background grid: structured quads (or triangles) on [0, 0.6] x [0, 0.12],
Body mesh: the same cells over the column, the material points are created by
Kratos (MATERIAL_POINTS_PER_ELEMENT) inside each body cell.

Usage: make_case.py OUTDIR --h 0.01 [--elem quad|tri] [--mp 4] [--dt 1e-3]
                     [--floor friction|fixed|slip] [--mu 0.36] [--pen 1e8]
                     [--wall slip|fixed] [--tend 1.0] [--scheme newmark|bossak]
"""
import argparse
import json
import math
import os


def element_lines(lines, nx, ny, node, prop, elem):
    """Append the elements of an nx x ny structured block (quads, or two
    triangles per quad) with property id prop to lines; return their ids."""
    ids = []
    for j in range(ny):
        for i in range(nx):
            n1, n2, n3, n4 = node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)
            cells = [(n1, n2, n3, n4)] if elem == "quad" else [(n1, n2, n3), (n1, n3, n4)]
            for conn in cells:
                ids.append(len(ids) + 1)
                lines.append(f"{ids[-1]} {prop} " + " ".join(str(n) for n in conn))
    return ids


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir")
    ap.add_argument("--h", type=float, default=0.01)
    ap.add_argument("--elem", choices=["quad", "tri"], default="quad")
    ap.add_argument("--mp", type=int, default=None,
                    help="material points per body element (quad 4, tri 3)")
    ap.add_argument("--dt", type=float, default=1e-3)
    ap.add_argument("--tend", type=float, default=1.0)
    ap.add_argument("--floor", choices=["friction", "fixed", "slip"], default="friction")
    ap.add_argument("--mu", type=float, default=0.36)
    ap.add_argument("--pen", type=float, default=1e8,
                    help="tangential penalty coefficient of the frictional slip process")
    ap.add_argument("--normal_option", default="flip_normal", help="option of the slip process: flip_normal or empty")
    ap.add_argument("--wall", choices=["slip", "fixed"], default="slip")
    ap.add_argument("--scheme", choices=["newmark", "bossak"], default="newmark")
    ap.add_argument("--alpha", type=float, default=-0.3, help="Bossak alpha (damp_factor_m)")
    ap.add_argument("--law", default="HenckyMCPlasticPlaneStrain2DLaw")
    ap.add_argument("--phi", type=float, default=19.8)
    ap.add_argument("--lx", type=float, default=0.6)
    ap.add_argument("--ly", type=float, default=0.12)
    ap.add_argument("--maxit", type=int, default=20)
    ap.add_argument("--up", action="store_true",
                    help="mixed displacement-pressure (UP) formulation with PPP stabilisation and the UP Mohr-Coulomb law")
    ap.add_argument("--rtol", type=float, default=1e-4)
    ap.add_argument("--crit", choices=["residual_criterion", "displacement_criterion"],
                    default="residual_criterion")
    ap.add_argument("--out_interval", type=float, default=0.05)
    ap.add_argument("--body_w", type=float, default=0.2, help="column width (sliding-block test: other sizes)")
    ap.add_argument("--body_h", type=float, default=0.1)
    ap.add_argument("--body_x0", type=float, default=0.0)
    ap.add_argument("--v0", type=float, default=0.0, help="initial x velocity of all points (sliding-block test)")
    a = ap.parse_args()

    h = a.h
    nx = int(round(a.lx / h))
    ny = int(round(a.ly / h))
    bx = int(round(a.body_w / h))
    by = int(round(a.body_h / h))
    os.makedirs(a.outdir, exist_ok=True)

    def nid(i, j):
        return j * (nx + 1) + i + 1

    # ---------------- grid ----------------
    lines = ["Begin ModelPartData", "End ModelPartData", "",
             "Begin Properties 0", "End Properties", "", "Begin Nodes"]
    for j in range(ny + 1):
        for i in range(nx + 1):
            lines.append(f"{nid(i, j)} {i * h:.10f} {j * h:.10f} 0.0")
    lines.append("End Nodes")
    lines.append("")
    lines.append("Begin Elements Element2D4N" if a.elem == "quad" else "Begin Elements Element2D3N")
    elems = element_lines(lines, nx, ny, nid, 0, a.elem)
    lines.append("End Elements")
    lines.append("")
    floor_nodes = [nid(i, 0) for i in range(nx + 1)]
    wall_nodes = [nid(0, j) for j in range(ny + 1)]
    # floor line conditions (left to right, as in Kratos' friction test, with flip_normal)
    floor_conds = []
    if a.floor in ("friction", "slip"):
        lines.append("Begin Conditions LineCondition2D2N")
        for i in range(nx):
            floor_conds.append(i + 1)
            lines.append(f"{i + 1} 0 {nid(i, 0)} {nid(i + 1, 0)}")
        lines.append("End Conditions")
        lines.append("")

    def smp(name, nodes, elements=(), conds=()):
        out = [f"Begin SubModelPart {name}", "    Begin SubModelPartNodes"]
        out += [f"        {n}" for n in nodes]
        out += ["    End SubModelPartNodes", "    Begin SubModelPartElements"]
        out += [f"        {e}" for e in elements]
        out += ["    End SubModelPartElements", "    Begin SubModelPartConditions"]
        out += [f"        {c}" for c in conds]
        out += ["    End SubModelPartConditions", "End SubModelPart"]
        return out

    lines += smp("Parts_Grid", list(range(1, (nx + 1) * (ny + 1) + 1)), elems)
    lines += smp("Wall", wall_nodes)
    if a.floor == "fixed":
        lines += smp("Floor", floor_nodes)
    else:
        lines += smp("Floor", floor_nodes, (), floor_conds)
    with open(os.path.join(a.outdir, "case_Grid.mdpa"), "w") as f:
        f.write("\n".join(lines) + "\n")

    # ---------------- body ----------------
    lines = ["Begin ModelPartData", "End ModelPartData", "",
             "Begin Properties 1", "End Properties", "", "Begin Nodes"]
    for j in range(by + 1):
        for i in range(bx + 1):
            lines.append(f"{j * (bx + 1) + i + 1} {a.body_x0 + i * h:.10f} {j * h:.10f} 0.0")
    lines.append("End Nodes")

    def bid(i, j):
        return j * (bx + 1) + i + 1
    kind = ("MPMUpdatedLagrangianUP2D" if a.up else "MPMUpdatedLagrangian2D") + \
        ("4N" if a.elem == "quad" else "3N")
    lines.append(f"Begin Elements {kind}")
    belems = element_lines(lines, bx, by, bid, 1, a.elem)
    lines.append("End Elements")
    lines += smp("Parts_Material_domain", list(range(1, (bx + 1) * (by + 1) + 1)), belems)
    with open(os.path.join(a.outdir, "case_Body.mdpa"), "w") as f:
        f.write("\n".join(lines) + "\n")

    mp = a.mp if a.mp else (4 if a.elem == "quad" else 3)
    if a.up and a.law == "HenckyMCPlasticPlaneStrain2DLaw":
        a.law = "HenckyMCPlasticPlaneStrainUP2DLaw"
    materials = {"properties": [{
        "model_part_name": "Initial_MPM_Material.Parts_Material_domain",
        "properties_id": 1,
        "Material": {
            "constitutive_law": {"name": a.law},
            "Variables": {
                "THICKNESS": 1.0,
                "MATERIAL_POINTS_PER_ELEMENT": mp,
                "DENSITY": 2650.0,
                "YOUNG_MODULUS": 0.84e6,
                "POISSON_RATIO": 0.3,
                "COHESION": 0.0,
                "INTERNAL_FRICTION_ANGLE": math.radians(a.phi),
                "INTERNAL_DILATANCY_ANGLE": 0.0,
            },
            "Tables": {}}}]}
    with open(os.path.join(a.outdir, "materials.json"), "w") as f:
        json.dump(materials, f, indent=2)

    constraints = [{
        "python_module": "assign_vector_variable_process",
        "kratos_module": "KratosMultiphysics",
        "Parameters": {
            "model_part_name": "Background_Grid.Wall",
            "variable_name": "DISPLACEMENT",
            "constrained": [True, a.wall == "fixed", True],
            "value": [0.0, 0.0 if a.wall == "fixed" else None, 0.0],
            "interval": [0.0, "End"]}}]
    if a.wall != "fixed":
        constraints[0]["Parameters"]["constrained"] = [True, False, True]
        constraints[0]["Parameters"]["value"] = [0.0, None, 0.0]
    other = []
    if a.floor == "fixed":
        constraints.append({
            "python_module": "assign_vector_variable_process",
            "kratos_module": "KratosMultiphysics",
            "Parameters": {
                "model_part_name": "Background_Grid.Floor",
                "variable_name": "DISPLACEMENT",
                "constrained": [True, True, True],
                "value": [0.0, 0.0, 0.0],
                "interval": [0.0, "End"]}})
    elif a.floor == "slip":
        # frictionless: fix only the normal (y) displacement
        constraints.append({
            "python_module": "assign_vector_variable_process",
            "kratos_module": "KratosMultiphysics",
            "Parameters": {
                "model_part_name": "Background_Grid.Floor",
                "variable_name": "DISPLACEMENT",
                "constrained": [False, True, True],
                "value": [None, 0.0, 0.0],
                "interval": [0.0, "End"]}})
    else:
        other.append({
            "python_module": "apply_mpm_slip_boundary_process",
            "kratos_module": "KratosMultiphysics.MPMApplication",
            "process_name": "ApplyMPMSlipBoundaryProcess",
            "Parameters": {
                "model_part_name": "Background_Grid.Floor",
                "friction_coefficient": a.mu,
                "tangential_penalty_coefficient": a.pen,
                "option": a.normal_option}})

    if a.v0 != 0.0:
        other.append({
            "python_module": "assign_initial_velocity_to_material_point_process",
            "kratos_module": "KratosMultiphysics.MPMApplication",
            "process_name": "AssignInitialVelocityToMaterialPointProcess",
            "Parameters": {"model_part_name": "Initial_MPM_Material.Parts_Material_domain",
                           "modulus": a.v0, "direction": [1.0, 0.0, 0.0]}})
    params = {
        "problem_data": {"problem_name": "bui2008", "parallel_type": "OpenMP",
                         "echo_level": 0, "start_time": 0.0, "end_time": a.tend},
        "solver_settings": {
            "time_stepping": {"time_step": a.dt},
            "solver_type": "Dynamic",
            "model_part_name": "MPM_Material",
            "domain_size": 2,
            "echo_level": 0,
            "analysis_type": "non_linear",
            "time_integration_method": "implicit",
            "scheme_type": a.scheme,
            "damp_factor_m": a.alpha,
            "newmark_beta": 0.25,
            "model_import_settings": {"input_type": "mdpa", "input_filename": "case_Body"},
            "material_import_settings": {"materials_filename": "materials.json"},
            "convergence_criterion": a.crit,
            "displacement_relative_tolerance": a.rtol,
            "displacement_absolute_tolerance": 1e-9,
            "residual_relative_tolerance": a.rtol,
            "residual_absolute_tolerance": 1e-9,
            "max_iteration": a.maxit,
            "grid_model_import_settings": {"input_type": "mdpa", "input_filename": "case_Grid"},
            "pressure_dofs": bool(a.up),
            "stabilization": "ppp",
            "linear_solver_settings": {"solver_type": "LinearSolversApplication.sparse_lu"},
            "auxiliary_variables_list": ["NORMAL", "IS_STRUCTURE"],
        },
        "processes": {
            "constraints_process_list": constraints,
            "loads_process_list": [],
            "list_other_processes": other,
            "gravity": [{
                "python_module": "assign_gravity_to_material_point_process",
                "kratos_module": "KratosMultiphysics.MPMApplication",
                "process_name": "AssignGravityToMaterialPointProcess",
                "Parameters": {"model_part_name": "MPM_Material",
                               "variable_name": "MP_VOLUME_ACCELERATION",
                               "modulus": 9.81, "direction": [0.0, -1.0, 0.0]}}],
        },
        "output_processes": {},
        "_case": vars(a),
    }
    case = params.pop("_case")
    with open(os.path.join(a.outdir, "ProjectParameters.json"), "w") as f:
        json.dump(params, f, indent=2)
    with open(os.path.join(a.outdir, "case.json"), "w") as f:
        json.dump(case, f, indent=2)


if __name__ == "__main__":
    main()
