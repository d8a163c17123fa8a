// Where the blurs (bilateral_separable.comp, bilateral_2d.comp) read the guide planes: BilateralConstants'
// guideStep and guideWidth (layouts.h), with 0 meaning planes of the image's own size, as a host that zeroes
// the block gets. The includer declares the push constants as `k`.

int bilateralGuideStep() { return max(k.guideStep, 1); }

// Index in the depth plane (3 times it in the normal plane) of image pixel (x, y).
uint bilateralGuideIndex(int x, int y) {
    const int step = bilateralGuideStep();
    const int width = step > 1 ? k.guideWidth : k.width;
    return uint(y * step) * uint(width) + uint(x * step);
}
