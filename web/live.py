"""What the scripts that drive the live page (page_checks.py, page_timing.py) share: when a
page is ready, where a model point is on the screen, waiting for a change to settle."""
import time

# The page has solved and drawn its scene, and made the rest (sheets, diagrams, modes).
READY = "typeof live === 'object' && live !== null && document.body.dataset.state === 'idle'"
# Client (CSS pixel) position of a model point in the picture shown (the page's own map).
TO_SCREEN = "toScreen"


def settle(page, timeout=30):
    """Waits until the page has made the rest of its last change (sheets, diagrams, modes)."""
    end = time.time() + timeout
    while time.time() < end:
        if page.eval("document.body.dataset.state === 'idle'"):
            return
        time.sleep(0.02)
    raise RuntimeError("the page did not settle")
