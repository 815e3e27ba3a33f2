"""Headless Debian Chromium driven by Debian's chromedriver through python3-selenium, for the browser tests.

The flags are the ones this kind of machine needs (docs/serve.md): no sandbox as root, no GPU, and no background
networking (a closed network refuses Chromium's own connections many at a time). Each session gets a fresh profile.
Screenshots go under the build tree (NEEDLEKIT_SCREENSHOT_DIR) and their paths are printed, so that a person can look
at them after `ctest --output-on-failure -R browser`.
"""
import contextlib
import os
import pathlib
import tempfile

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
SCREENSHOT_DIR = pathlib.Path(os.environ.get("NEEDLEKIT_SCREENSHOT_DIR", "build/browser-screenshots"))


@contextlib.contextmanager
def chromium(width=1280, height=900):
    """A headless Chromium WebDriver; browser console messages are readable through driver.get_log('browser')."""
    with tempfile.TemporaryDirectory(prefix="needlekit-chromium-") as profile:
        options = webdriver.ChromeOptions()
        options.binary_location = CHROMIUM
        for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--use-gl=swiftshader",
                     "--enable-unsafe-swiftshader", "--disable-quic", "--no-first-run",
                     "--disable-background-networking", "--disable-component-update", "--disable-sync",
                     "--disable-dev-shm-usage", "--allow-file-access-from-files",
                     f"--user-data-dir={profile}", f"--window-size={width},{height}"):
            options.add_argument(flag)
        options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
        driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
        try:
            yield driver
        finally:
            driver.quit()


def console_errors(driver):
    """The browser console's SEVERE entries since the last call."""
    return [entry for entry in driver.get_log("browser") if entry.get("level") == "SEVERE"]


def screenshot(driver, name):
    """Saves a PNG under SCREENSHOT_DIR, prints its path for the test log and returns it."""
    SCREENSHOT_DIR.mkdir(parents=True, exist_ok=True)
    path = SCREENSHOT_DIR / f"{name}.png"
    driver.save_screenshot(str(path))
    print(f"screenshot: {path.resolve()}")
    return path
