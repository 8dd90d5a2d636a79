"""engstad-vndf-proof (Engstad, visible GGX), figures 3 and 7: the VNDF pdf from the top for alpha = (0.15, 0.5), theta_v = 75
degrees and phi_v = 0, 90; grey: normals that reflect the view into the upper hemisphere. Usage: [out.png]"""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import ggx

shape = ggx.Shape.aniso(0.15, 0.5)
x, y = np.meshgrid(np.linspace(-1, 1, 501), np.linspace(-1, 1, 501))
m = np.stack([x, y, np.sqrt(np.clip(1 - x * x - y * y, 0, 1))], axis=-1)
disk = x * x + y * y < 1
fig, axes = plt.subplots(1, 2, figsize=(9.5, 4.4), constrained_layout=True)
for ax, phi in zip(axes, (0, 90)):
    t, p = np.radians(75), np.radians(phi)
    v = np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])
    pdf = np.where(disk, ggx.pdf_vndf(shape, v, m), np.nan)
    up = disk & (ggx.reflect(v, m)[..., 2] > 0)
    im = ax.imshow(pdf, extent=(-1, 1, -1, 1), origin="lower", cmap="viridis")
    ax.imshow(np.where(up, 0.5, np.nan), extent=(-1, 1, -1, 1), origin="lower", cmap="gray", vmin=0, vmax=1,
              alpha=0.45)
    ax.annotate("v", xy=(0.96 * v[0] / np.hypot(v[0], v[1]), 0.96 * v[1] / np.hypot(v[0], v[1])), color="red")
    ax.set(title=f"$\\theta_v$ = 75°, $\\phi_v$ = {phi}°", xlabel="$m_x$", ylabel="$m_y$", aspect="equal")
    fig.colorbar(im, ax=ax, shrink=0.8, label="pdf (1/sr)")
    print(f"phi_v = {phi}: peak {np.nanmax(pdf):.3f}, grey {np.mean(up[disk]):.3f} of the disk")
fig.suptitle("Visible normals of GGX, $\\alpha$ = (0.15, 0.5), seen from the top (grey: reflection above the horizon)")
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "seed_figures.png", dpi=120)
