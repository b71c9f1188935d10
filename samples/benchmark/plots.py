"""PNG charts drawn with cv2 (matplotlib is not a project dependency)."""
import numpy as np
import cv2

PALETTE = [(180, 119, 31), (14, 127, 255), (44, 160, 44), (40, 39, 214), (189, 103, 148),
           (75, 86, 140), (194, 119, 227), (127, 127, 127), (34, 189, 188), (207, 190, 23),
           (0, 0, 0), (120, 200, 120)]
FONT = cv2.FONT_HERSHEY_SIMPLEX
LEFT, RIGHT, TOP, BOTTOM = 80, 260, 60, 70  # margins; the legend sits in the right one


def _canvas(width, height, title):
    image = np.full((height, width, 3), 255, np.uint8)
    cv2.putText(image, title, (LEFT, 22), FONT, 0.6, (0, 0, 0), 1, cv2.LINE_AA)
    return image


def _axes(image, x_ticks, y_ticks, to_px, x_label, y_label):
    height, width = image.shape[:2]
    cv2.rectangle(image, (LEFT, TOP), (width - RIGHT, height - BOTTOM), (0, 0, 0), 1)
    for value, text in x_ticks:
        x, _ = to_px(value, 0)
        cv2.line(image, (x, height - BOTTOM), (x, height - BOTTOM + 5), (0, 0, 0), 1)
        cv2.putText(image, text, (x - 12, height - BOTTOM + 20), FONT, 0.4, (0, 0, 0), 1,
                    cv2.LINE_AA)
    for value, text in y_ticks:
        _, y = to_px(0, value)
        cv2.line(image, (LEFT, y), (width - RIGHT, y), (225, 225, 225), 1)
        cv2.putText(image, text, (LEFT - 45, y + 4), FONT, 0.4, (0, 0, 0), 1, cv2.LINE_AA)
    cv2.putText(image, x_label, (LEFT + 200, height - 20), FONT, 0.5, (0, 0, 0), 1, cv2.LINE_AA)
    cv2.putText(image, y_label, (5, TOP - 10), FONT, 0.5, (0, 0, 0), 1, cv2.LINE_AA)


def _legend(image, names):
    x = image.shape[1] - RIGHT + 15
    for k, name in enumerate(names):
        y = TOP + 10 + 22 * k
        cv2.rectangle(image, (x, y - 8), (x + 20, y + 4), PALETTE[k % len(PALETTE)], -1)
        cv2.putText(image, name, (x + 28, y + 3), FONT, 0.45, (0, 0, 0), 1, cv2.LINE_AA)


def cumulative_curves(path, title, errors_by_method, max_error=10.0, x_label="error, degrees"):
    """One curve per method: the fraction of runs with an error at most x (a run without a
    model counts as an infinite error)."""
    width, height = 1100, 600
    image = _canvas(width, height, title)

    def to_px(x, y):
        return (int(LEFT + x / max_error * (width - LEFT - RIGHT)),
                int(height - BOTTOM - y * (height - TOP - BOTTOM)))

    _axes(image, [(v, "%g" % v) for v in np.linspace(0, max_error, 11)],
          [(v, "%.1f" % v) for v in np.linspace(0, 1, 6)], to_px, x_label,
          "fraction of runs")
    grid = np.linspace(0, max_error, 400)
    # drawn last to first, so the first methods (rcme's) stay visible where curves coincide
    for k, (name, errors) in reversed(list(enumerate(errors_by_method.items()))):
        errors = np.sort(np.asarray(errors, np.float64))
        if len(errors) == 0:
            continue
        fraction = np.searchsorted(errors, grid, side="right") / len(errors)
        points = np.array([to_px(x, y) for x, y in zip(grid, fraction)], np.int32)
        cv2.polylines(image, [points], False, PALETTE[k % len(PALETTE)], 2, cv2.LINE_AA)
    _legend(image, list(errors_by_method))
    cv2.imwrite(path, image)


def grouped_bars(path, title, groups, methods, values, y_label, max_value=None):
    """values[g][m]: a bar per method in each group (NaN: no bar, e.g. the method does not
    apply)."""
    width, height = 1300, 600
    image = _canvas(width, height, title)
    finite = [v for row in values for v in row if np.isfinite(v)]
    top = max_value or max(5.0, (max(finite) if finite else 5.0) * 1.1)
    top = np.ceil(top / 5.0) * 5.0  # ticks at multiples of 1 (up to 5) or of 5
    plot_width = width - LEFT - RIGHT
    group_width = plot_width / max(len(groups), 1)
    bar_width = group_width * 0.85 / max(len(methods), 1)

    def to_px(x, y):
        return int(LEFT + x), int(height - BOTTOM - y / top * (height - TOP - BOTTOM))

    _axes(image, [], [(v, "%g" % v) for v in np.linspace(0, top, 6)], to_px, "", y_label)
    for g, group in enumerate(groups):
        x_start = g * group_width + group_width * 0.075
        for m in range(len(methods)):
            value = values[g][m]
            if not np.isfinite(value):
                continue
            x1, y1 = to_px(x_start + m * bar_width, value)
            x2, y2 = to_px(x_start + (m + 1) * bar_width - 1, 0)
            cv2.rectangle(image, (x1, min(y1, y2 - 1)), (x2, y2), PALETTE[m % len(PALETTE)], -1)
        label_x, _ = to_px(g * group_width + 5, 0)
        cv2.putText(image, group, (label_x, height - BOTTOM + 20), FONT, 0.42, (0, 0, 0), 1,
                    cv2.LINE_AA)
    _legend(image, methods)
    cv2.imwrite(path, image)


def reliability_scatter(path, title, points_by_group, unit="deg"):
    """Log-log scatter, one colour per group: x the predicted standard deviation of a run, y its
    actual error (same unit); the diagonal y = x is where a calibrated covariance scatters."""
    width, height = 1000, 700
    image = _canvas(width, height, title)
    values = np.concatenate([np.r_[x, y] for x, y in points_by_group.values()] or [[1e-3, 1]])
    values = values[values > 0]
    low = 10 ** np.floor(np.log10(values.min()))
    high = 10 ** np.ceil(np.log10(values.max()))
    decades = np.log10(high / low)

    def to_px(x, y):
        u = np.log10(max(x, low) / low) / decades
        v = np.log10(max(y, low) / low) / decades
        return (int(LEFT + u * (width - LEFT - RIGHT)),
                int(height - BOTTOM - v * (height - TOP - BOTTOM)))

    ticks = [(10 ** e, "%g" % 10 ** e) for e in np.arange(np.log10(low), np.log10(high) + 0.5)]
    _axes(image, ticks, ticks, to_px, "predicted std, " + unit, "actual error, " + unit)
    cv2.line(image, to_px(low, low), to_px(high, high), (0, 0, 0), 1, cv2.LINE_AA)
    for k, (x, y) in enumerate(points_by_group.values()):
        for a, b in zip(x, y):
            cv2.circle(image, to_px(a, b), 4, PALETTE[k % len(PALETTE)], -1, cv2.LINE_AA)
    _legend(image, list(points_by_group))
    cv2.imwrite(path, image)
