"""Fails when a screenshot of the certificate is blank or unstyled.

Checks: enough ink (non-white pixels), enough distinct colours (text anti-aliasing, figures), and
the solid colours of the page's own styling: the green "consistent" badge, and on the certify page
the red "proved empty" badge; on the accuracy page (no verdict), the brackets' blue bars.
"""
import sys

from PIL import Image

BADGES = {
    "consistent": (0x2A, 0x7D, 0x2A),
    "proved empty": (0xB5, 0x2A, 0x2A),
    "bracket bars": (0x4A, 0x78, 0xC2),
}


def near(a, b, tol=6):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def main(path, name):
    image = Image.open(path).convert("RGB")
    width, height = image.size
    data = image.tobytes()
    pixels = list(zip(data[0::3], data[1::3], data[2::3]))
    ink = sum(1 for p in pixels if p != (255, 255, 255)) / len(pixels)
    colours = len(set(pixels))
    print(f"{name}: {width}x{height}, {ink:.1%} ink, {colours} colours")
    problems = []
    if ink < 0.03:
        problems.append(f"only {ink:.2%} of the pixels are not white")
    if colours < 50:
        problems.append(f"only {colours} distinct colours")
    if name == "accuracy":
        wanted = ["bracket bars"]
    else:
        wanted = ["consistent"] + (["proved empty"] if name == "certificate" else [])
    for badge in wanted:
        count = sum(1 for p in pixels if near(p, BADGES[badge]))
        if count < 100:
            problems.append(f"the '{badge}' badge is not drawn ({count} pixels of its colour)")
    if problems:
        sys.exit(f"{path}: blank or unstyled page: " + "; ".join(problems))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
