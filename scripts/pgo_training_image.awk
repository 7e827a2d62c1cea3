# scripts/pgo_training_image.awk — prints the generated training image of build_release.sh.
# A PBM (P1) training image larger than Chromium's 512-px tiles: ellipses, rings, bars,
# and a block of noise (awk's own random numbers; any values do).
BEGIN {
    W = 1100; H = 800; srand(7); n = 0
    for (k = 0; k < 60; k++) {
        cx[k] = 40 + rand() * (W - 80); cy[k] = 40 + rand() * (H - 80)
        rx[k] = 4 + rand() * 70; ry[k] = 4 + rand() * 70; a[k] = rand() * 3.14159
        ring[k] = (rand() < 0.3)
    }
    print "P1"; print W, H
    for (y = 0; y < H; y++) {
        line = ""
        for (x = 0; x < W; x++) {
            v = 0
            if (x >= 900 && x < 1060 && y >= 600 && y < 760) v = (rand() < 0.5)
            else if (y % 97 < 3 && x > 20 && x < 500) v = 1
            else for (k = 0; k < 60; k++) {
                dx = x - cx[k]; dy = y - cy[k]
                if (dx > 75 || dx < -75 || dy > 75 || dy < -75) continue
                u = (dx * cos(a[k]) + dy * sin(a[k])) / rx[k]
                w = (-dx * sin(a[k]) + dy * cos(a[k])) / ry[k]
                d = u * u + w * w
                if (d <= 1 && (!ring[k] || d >= 0.6)) { v = 1 - v }
            }
            line = line v
            if (length(line) >= 70) { print line; line = "" }
        }
        if (line != "") print line
    }
}
