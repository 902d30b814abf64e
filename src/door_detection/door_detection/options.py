"""Options of the door detector, validated on construction.

Every field's docstring gives its unit, the interval enforced by
:meth:`DetectionOptions.__post_init__` and, where the value comes from the paper
([Banerjee 2015], Banerjee et al., WPI-CMU DRC Finals), the section it is taken from.
Pixel quantities refer to the **full-resolution** image unless stated otherwise; the
2-D stage runs on an image scaled by ``line_scale`` and converts back.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from door_contract.ranges import FieldRange, check_in_range
from door_detection.errors import DetectionError

__all__ = ["DetectionOptions", "option_range"]


def _ranges() -> dict[str, FieldRange]:
    """Interval of every option (a function, so no module-level mutable state)."""
    r = FieldRange
    return {
        "line_scale": r(0.1, 1.0, "", low_open=True),
        "histogram_clip_limit": r(0.0, 40.0, ""),
        "bilateral_diameter": r(1, 15, "px"),
        "bilateral_sigma_color": r(0.0, 255.0, "grey levels", low_open=True),
        "bilateral_sigma_space": r(0.0, 50.0, "px", low_open=True),
        "canny_low": r(1, 1000, "grey-level gradient"),
        "canny_high": r(1, 1000, "grey-level gradient"),
        "hough_rho": r(0.0, 10.0, "px", low_open=True),
        "hough_theta_deg": r(0.0, 10.0, "deg", low_open=True),
        "hough_threshold": r(1, 1000, "votes"),
        "hough_max_gap": r(0.0, 200.0, "px"),
        "min_line_length": r(4.0, 5000.0, "px"),
        "max_line_tilt_deg": r(0.0, 45.0, "deg", low_open=True),
        "max_lines": r(2, 200, "lines"),
        "line_merge_distance": r(0.0, 50.0, "px"),
        "min_pair_separation": r(0.0, 2000.0, "px"),
        "min_vertical_overlap": r(0.0, 1.0, ""),
        "edge_depth_offset": r(0, 30, "px"),
        "door_width_min": r(0.3, 2.0, "m"),
        "door_width_max": r(0.3, 2.5, "m"),
        "door_width_tolerance": r(0.0, 0.2, "m"),
        "min_depth": r(0.0, 5.0, "m", low_open=True),
        "max_depth": r(0.5, 100.0, "m"),
        "max_depth_noise": r(0.0, 1.0, "m", low_open=True),
        "line_ransac_threshold": r(0.0, 0.5, "m", low_open=True),
        "line_ransac_iterations": r(1, 10000, "hypotheses"),
        "line_max_points": r(8, 100000, "points"),
        "min_line_inlier_fraction": r(0.0, 1.0, "", low_open=True),
        "max_edge_angle_deg": r(0.0, 90.0, "deg", low_open=True),
        "duplicate_distance": r(0.0, 1.0, "m"),
        "frame_width_max": r(0.0, 0.5, "m"),
        "plane_inlier_distance": r(0.0, 0.5, "m", low_open=True),
        "diagonal_samples": r(4, 10000, "samples"),
        "min_plane_inlier_fraction": r(0.0, 1.0, "", low_open=True),
        "plane_max_points": r(16, 1000000, "points"),
        "max_candidates": r(1, 100, "doors"),
        "handle_sigma_scale": r(0.0, 10.0, "σ", low_open=True),
        "handle_min_sigma": r(0.0, 128.0, "levels"),
        "handle_min_area": r(1.0, 100000.0, "px"),
        "handle_min_area_fraction": r(0.0, 1.0, ""),
        "handle_max_area_fraction": r(0.0, 1.0, "", low_open=True),
        "handle_max_aspect": r(0.1, 20.0, ""),
        "handle_band_low": r(0.0, 1.0, ""),
        "handle_band_high": r(0.0, 1.0, ""),
        "handle_side_fraction": r(0.05, 0.5, ""),
        "door_margin_fraction": r(0.0, 0.3, ""),
        "max_handle_standoff": r(0.0, 0.5, "m"),
        "lever_grasp_fraction": r(0.0, 1.0, ""),
        "handle_standoff_prior": r(0.0, 0.5, "m"),
        "handle_standoff_prior_sigma": r(0.0, 1.0, "m"),
        "lever_min_elongation": r(1.0, 20.0, ""),
        "lever_max_half_section": r(0.0, 0.1, "m"),
        "scribble_region_width": r(0.02, 2.0, "m"),
        "scribble_region_height": r(0.02, 2.0, "m"),
        "scribble_exclusion": r(0.0, 0.5, "m"),
        "scribble_dilation": r(0, 50, "px"),
        "operator_ransac_iterations": r(3, 100000, "iterations"),
        "min_region_points": r(3, 100000, "points"),
        "min_valid_fraction": r(0.0, 1.0, ""),
        "vote_frames": r(1, 100, "frames"),
        "vote_handle_distance": r(0.0, 1.0, "m", low_open=True),
        "vote_normal_angle_deg": r(0.0, 90.0, "deg", low_open=True),
        "vote_min_agreeing": r(1, 100, "frames"),
        "vote_handle_confidence": r(0.0, 0.1, "m", low_open=True),
        "vote_normal_confidence_deg": r(0.0, 10.0, "deg", low_open=True),
        "random_seed": r(0, 2**31 - 1, ""),
    }



def option_range(name: str) -> FieldRange:
    """The allowed interval of option ``name`` (the order of paired options is checked apart):
    what a node parameter configuring that option takes as its range."""
    return _ranges()[name]

@dataclass(frozen=True)
class DetectionOptions:
    """Thresholds of the automatic (Sec. III-A) and operator-aided (Sec. III-B) detectors
    and of the vote."""

    # --- 2-D stage: filtering, edges, lines (Sec. III-A, "image filtering") ---
    line_scale: float = 1.0
    """Scale of the image the 2-D stage runs on, (0.1, 1]. Halving the frame makes the
    bilateral filter, Canny and Hough ~4× cheaper (13.6 instead of 18.9 ms at 1024×544),
    but at 3 m a jamb's two edges (6 cm, ~12 px) then fuse into one line, the frame's
    outer edge replaces the leaf's, and the width (hence the hinge the door motions turn
    about) is off by 4–8 cm. On the real photos full scale finds as many doors but more
    clutter (see RESULTS.md)."""
    histogram_clip_limit: float = 4.0
    """Contrast limit of the histogram equalisation (× the mean bin height), [0, 40]; 0 is the
    paper's plain equalisation (Sec. III-A: "histogram equalization"), which erases small
    steps next to a dominant grey (see ``preprocessing.equalise_luma``). Any clip keeps an
    11-level step of a white scene; on the 31 real photos (``door_evaluation.detection.evaluate_photos``)
    4 found as many doors as plain equalisation (17 of 35) and 2 only 12."""
    bilateral_diameter: int = 5
    """Bilateral filter neighbourhood diameter (px of the scaled image), [1, 15]
    (Sec. III-A: "a bilateral filter is applied to smooth the image")."""
    bilateral_sigma_color: float = 30.0
    """Bilateral filter range sigma (grey levels), (0, 255]."""
    bilateral_sigma_space: float = 3.0
    """Bilateral filter spatial sigma (px of the scaled image), (0, 50]."""
    canny_low: int = 10
    """Canny hysteresis low threshold (gradient magnitude), [1, 1000] (Sec. III-A)."""
    canny_high: int = 30
    """Canny hysteresis high threshold (gradient magnitude), [1, 1000], >= canny_low. A grey-blue
    leaf in a grey frame differs by ~9 levels in each YCrCb channel, which OpenCV's 3×3 Sobel
    (L1 norm) makes a gradient of ~36: 45 lost that edge (the leaf then paired with the far
    jamb's outer edge, 1.05 m, and was refused); 30 keeps it."""
    hough_rho: float = 1.0
    """Probabilistic Hough distance resolution (px of the scaled image), (0, 10]."""
    hough_theta_deg: float = 0.5
    """Probabilistic Hough angle resolution (deg), (0, 10]."""
    hough_threshold: int = 25
    """Probabilistic Hough accumulator threshold (votes), [1, 1000]."""
    hough_max_gap: float = 12.0
    """Largest gap bridged inside one Hough segment (px, full resolution), [0, 200]."""
    min_line_length: float = 60.0
    """Shortest vertical line kept (px, full resolution), [4, 5000]. Sec. III-A: "only the
    vertical lines which have a pixel length greater than a threshold determined
    experimentally are kept". 60 px is a 2.08 m door seen from ~20 m at fy ≈ 600 px;
    short lines rather come from panels and frames."""
    max_line_tilt_deg: float = 20.0
    """Largest angle between a kept line and the image vertical (deg), (0, 45]. Door
    edges converge in the image when the head pitches down (at 1 m the camera looks
    ~25° down and the edges near the image border lean by up to ~15°)."""
    max_lines: int = 24
    """Longest vertical lines kept after merging (lines), [2, 200]; bounds the O(n²)
    pairing."""
    line_merge_distance: float = 4.0
    """Collinear fragments whose image x differ by less than this at every row are
    merged into one line (px, full resolution), [0, 50]."""
    # --- pairing and 3-D checks (Sec. III-A) ---
    min_pair_separation: float = 60.0
    """Pairs of lines closer than this are dropped (px, full resolution), [0, 2000].
    Sec. III-A: "Line pairs that have a pixel distance of less than 60 pixels ... are
    eliminated"; on a 1024-px-wide frame with fx ≈ 600 px this limits detection to
    about 9 m."""
    min_vertical_overlap: float = 0.5
    """The two edges of a pair must overlap vertically over this fraction of the shorter
    one, [0, 1] (not in the paper: two edges of one door share their rows)."""
    edge_depth_offset: int = 4
    """Depth is read this many pixels inside the candidate door from each edge (px, full
    resolution), [0, 30], so the edge's 3-D points lie on the door leaf, not on the
    frame or the background seen through the gap."""
    door_width_min: float = 0.80
    """Narrowest door accepted (m), [0.3, 2]. Sec. III-A: 90 ± 10 cm (DRC door 36 in)."""
    door_width_max: float = 1.00
    """Widest door accepted (m), [0.3, 2.5], >= door_width_min. Sec. III-A: 90 ± 10 cm."""
    door_width_tolerance: float = 0.03
    """The pairing gate accepts widths this much outside [door_width_min, door_width_max] (m),
    [0, 0.2]. Not in the paper: the gate measures between the Hough lines, which lie up to
    ~2 px outside the leaf (1.5 cm at 3 m with f = 415 px; a 1.00 m leaf measured 1.005–1.009 m);
    the width reported is measured again on the sub-pixel edges (:mod:`~door_detection.edges`)."""
    min_depth: float = 0.3
    """Nearer depth readings are invalid (m), (0, 5]."""
    max_depth: float = 8.0
    """Farther depth readings are invalid (m), [0.5, 100], > min_depth."""
    max_depth_noise: float = 0.10
    """Largest depth noise σ (m) measured along an edge or a diagonal for it to count as a
    smooth surface, (0, 1]. Beyond the paper: the line and plane thresholds widen to 3σ
    of the measured noise (stereo σ ≈ k·z², ~5 cm at 4 m for a MultiSense-like head);
    this caps them."""
    line_ransac_threshold: float = 0.03
    """Inlier distance of the RANSAC 3-D line fit of each edge (m), (0, 0.5] (Sec. III-A:
    "The line equations ... are found using RANSAC")."""
    line_ransac_iterations: int = 40
    """Hypotheses of each RANSAC line fit, [1, 10000] (all scored at once, vectorised)."""
    line_max_points: int = 160
    """Depth samples per edge (points), [8, 100000]."""
    min_line_inlier_fraction: float = 0.5
    """An edge whose RANSAC line explains less than this fraction of its valid samples
    is rejected, (0, 1]."""
    max_edge_angle_deg: float = 15.0
    """Largest 3-D angle between the two edges of a pair (deg), (0, 90]: door edges are
    parallel."""
    duplicate_distance: float = 0.05
    """Pairs whose edges both lie within this distance of another pair's are duplicates
    and merged (m), [0, 1]. Sec. III-A: "door pairs that have the same line equations
    are merged"."""
    frame_width_max: float = 0.15
    """Widest door frame (jamb face) expected around a leaf (m), [0, 0.5]. Beyond the paper:
    a pair nested inside another one by at most this much on both sides is the leaf inside
    its frame, and the outer pair (the frame's outer edges) is dropped."""
    plane_inlier_distance: float = 0.05
    """Points within this distance of the door plane are on the door (m), (0, 0.5].
    Sec. III-A: "the distance ... for any point on the door, is less than 5 cm from the
    door plane"."""
    diagonal_samples: int = 40
    """Samples on each of the two door diagonals (samples), [4, 10000]. Sec. III-A:
    "taking two diagonals in the door, sampling points on them"."""
    min_plane_inlier_fraction: float = 0.8
    """Fraction of the valid diagonal samples that must lie on the plane, (0, 1]."""
    plane_max_points: int = 3000
    """Door-surface samples used to refine the plane (points), [16, 1e6]."""
    max_candidates: int = 4
    """Best door candidates passed to handle detection (doors), [1, 100]."""
    # --- handle (Sec. III-A, second phase) ---
    handle_sigma_scale: float = 1.0
    """Door-coloured pixels are within handle_sigma_scale·σ of the door mean µ in every
    channel, (0, 10]. Sec. III-A: "pixel value within the range µ − σ and µ + σ"."""
    handle_min_sigma: float = 12.0
    """Floor of σ (grey levels), [0, 128]: a uniformly painted door has σ ≈ 0, which
    would make every pixel (noise) a handle pixel."""
    handle_min_area: float = 12.0
    """Smallest handle blob (px, full resolution), [1, 1e5]."""
    handle_min_area_fraction: float = 0.0004
    """Smallest handle blob as a fraction of the door's image area, [0, 1] (the paper's
    "contour area threshold"; a fraction keeps it valid at every distance)."""
    handle_max_area_fraction: float = 0.03
    """Largest handle blob as a fraction of the door's image area, (0, 1]."""
    handle_max_aspect: float = 2.0
    """A handle blob's bounding box is at most this many times taller than wide,
    [0.1, 20] (levers are horizontal, knobs round; frames and edges are tall)."""
    handle_band_low: float = 0.20
    """Bottom of the handle search band as a fraction of the door height from the
    bottom, [0, 1] (handles are 0.9–1.1 m up a 2.08 m door)."""
    handle_band_high: float = 0.80
    """Top of the handle search band (fraction of the door height), [0, 1], > low."""
    handle_side_fraction: float = 0.30
    """Width of each side strip searched for the handle (fraction of the door width),
    [0.05, 0.5]. Sec. III-A: "a region is selected ... to exclude the central part"."""
    door_margin_fraction: float = 0.04
    """Border of the door region ignored when computing µ, σ (fraction of the door
    width), [0, 0.3]: edge pixels mix door and frame."""
    max_handle_standoff: float = 0.15
    """Largest distance of the grasp point in front of the door plane (m), [0, 0.5]."""
    handle_standoff_prior: float = 0.065
    """Prior mean of the distance of a handle's visible surface from the door (m), [0, 0.5]
    (lever handles stand 5–8 cm proud; the DRC-size sim lever's front is at 7 cm). Not in
    the paper: fused with the measured stand-off, see ``grasp.fused_standoff``."""
    handle_standoff_prior_sigma: float = 0.015
    """Prior standard deviation of that stand-off (m), [0, 1]; 0 disables the prior."""
    lever_grasp_fraction: float = 0.6
    """Grasp point along a lever, from its axis towards its tip, as a fraction of the
    lever length, [0, 1] (not in the paper; the simulated DRC door's grasp convention,
    ``DoorConfig.grasp_fraction``)."""
    lever_min_elongation: float = 2.0
    """A handle blob longer than this many times its height is a lever, [1, 20];
    shorter blobs (knobs) are grasped at their centroid."""
    lever_max_half_section: float = 0.01
    """The grasp point lies half the bar's apparent height (at most this) behind the bar's
    visible surface (m), [0, 0.1]; the apparent height includes the top face seen from
    above, hence the cap (a 2-cm bar)."""
    # --- operator-aided (Sec. III-B) ---
    scribble_region_width: float = 0.55
    """Width of the region sampled beside the scribble, towards the door side (m),
    [0.02, 2]. Sec. III-B: "points offset on the side of the seeded point is sampled".
    A DRC door extends ~0.8 m from the handle to the hinge; a wide region keeps the
    normal within 1° under 5 cm depth noise (error ≈ σ/(extent·√N))."""
    scribble_region_height: float = 0.90
    """Height of the sampled region, centred on the scribble (m), [0.02, 2] (a handle
    at ~0.9 m leaves ±0.45 m of door above and below)."""
    scribble_exclusion: float = 0.03
    """Margin around the scribble's bounding box excluded from the sampled region (m),
    [0, 0.5], so the handle itself is not fitted as the door."""
    scribble_dilation: int = 4
    """The scribble polygon is grown by this many pixels before the handle pixels are
    segmented inside it, [0, 50]."""
    operator_ransac_iterations: int = 200
    """Iterations of Open3D ``segment_plane`` (iterations), [3, 1e5]."""
    min_valid_fraction: float = 0.3
    """Operator-aided: at least this fraction of the sampled region must have valid depth,
    [0, 1] (Sec. III-B/V: the method "failed when valid disparity values could not be
    obtained")."""
    min_region_points: int = 30
    """Fewest valid depth points a sampled region (or edge) needs (points), [3, 1e5]."""
    # --- vote over frames (Sec. III-A, last paragraph) ---
    vote_frames: int = 10
    """Window N of the vote (frames), [1, 100]. Sec. III-A: "the entire algorithm is
    repeated over a window of 10 frames"; here the vote may confirm before N frames (see
    :mod:`~door_detection.voting`)."""
    vote_handle_distance: float = 0.03
    """Two estimates agree when their handles are closer than this (m), (0, 1]."""
    vote_normal_angle_deg: float = 5.0
    """... and their normals differ by less than this (deg), (0, 90]."""
    vote_min_agreeing: int = 2
    """Agreeing estimates a door needs to be confirmed (frames), [1, 100], more than half of
    the window's estimates. Not in the paper (it waited for the full window): one frame can
    hold a wrong door, two agreeing ones from a still or moving camera rarely do."""
    vote_handle_confidence: float = 0.01
    """Largest half-width of the 95 % confidence interval of the confirmed handle,
    t₀.₉₇₅(n − 1)·‖s‖/√n over the n agreeing estimates (m), (0, 0.1]: half the 2 cm grasp
    tolerance ([Banerjee 2015] Sec. IV). Student's t makes two noisy frames that happen to agree
    wait (t = 12.7 for n = 2): with a standard error alone, 2 of 490 Table II doors were
    confirmed 2.3–3.4 cm off; exactly agreeing frames (clean depth) still confirm at n = 2."""
    vote_normal_confidence_deg: float = 1.0
    """Largest half-width of the 95 % confidence interval of the confirmed normal (deg),
    (0, 10]: half the 2° tolerance."""
    random_seed: int = 0
    """Seed of the RANSAC generators, so a run is reproducible, [0, 2^31 − 1]."""

    def __post_init__(self) -> None:
        ranges = _ranges()
        for spec in fields(self):
            check_in_range(spec.name, getattr(self, spec.name), ranges[spec.name], DetectionError,
                           integer=spec.type == "int")
        self._check_order("canny_low", "canny_high")
        self._check_order("door_width_min", "door_width_max")
        self._check_order("min_depth", "max_depth")
        self._check_order("handle_band_low", "handle_band_high")
        self._check_order("handle_min_area_fraction", "handle_max_area_fraction")

    def _check_order(self, low: str, high: str) -> None:
        if getattr(self, low) >= getattr(self, high):
            raise DetectionError(f"{low} = {getattr(self, low)!r} must be below "
                                 f"{high} = {getattr(self, high)!r}")

