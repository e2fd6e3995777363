component biscarakins "Kinematics of the BiSCARA robot (five-bar + Z + C), from biscara";

description """
Forward and inverse kinematics of a five-bar (5R) planar parallel robot that carries a vertical
prismatic axis and a rotary axis about Z, written by `biscara linuxcnc config`. The geometry, the
working and assembly modes, the joint limits and the singularity margin of the robot are HAL pins,
set by the configuration's HAL file from its robot.json, so one installed module serves every
robot file.

Joints: 0 theta1 (degrees), 1 theta2 (degrees), 2 d4 (mm), 3 theta3 (degrees).
Axes: X Y Z (mm) and C (degrees).

The formulas are those of `biscara ik` and `biscara fk`: each chain's root chosen by its working
mode; the inverse fails for a point a chain cannot reach, for a solution in the other assembly
mode (beyond a type-2 singularity) and for a pose inside the singularity margin. theta1 and
theta2 come out in (-180, 180], shifted by 360 when only that puts them inside their limits;
theta3 is unwrapped against its current value, so C turns continuously. The forward kinematics
fail only when the distal links cannot meet.

Build and install (as root): halcompile --install biscarakins.comp
""";

pin in float l1 "proximal link length, mm";
pin in float l2 "distal link length, mm";
pin in float b1x "x of chain 1's base joint, mm";
pin in float b2x "x of chain 2's base joint, mm";
pin in float lp "d4 = lp - z, mm";
pin in float sigma1 "working mode of chain 1: 1 (+) or -1 (-)";
pin in float sigma2 "working mode of chain 2: 1 (+) or -1 (-)";
pin in float sigma_a "assembly mode: 1 (+) or -1 (-)";
pin in float margin "singularity margin, degrees";
pin in float theta1_min "theta1's lower limit, degrees";
pin in float theta1_max "theta1's upper limit, degrees";
pin in float theta2_min "theta2's lower limit, degrees";
pin in float theta2_max "theta2's upper limit, degrees";
option singleton yes;
option extra_setup yes;
option period no;
function _ "does nothing: the motion controller calls the kinematics";
license "GPL";
author "biscara (generated)";
;;

#include "rtapi_math.h"
#include "kinematics.h"

/* Which source this module was built from: `biscara linuxcnc run` reinstalls a module whose
   mark differs from the source it would build. */
static const char source_mark[] __attribute__((used)) = "biscara-kinematics-source @SOURCE_ID@";

#define TAU (2.0 * M_PI)
#define DEGREE (M_PI / 180.0)

/* The one instance, whose pins the kinematics read. */
static struct __comp_state *robot;

EXTRA_SETUP() {
    (void)prefix;
    (void)extra_arg;
    robot = __comp_inst;
    return 0;
}

FUNCTION(_) {
}
/* The robot's numbers for one call, read from the pins: millimetres and radians. */
struct geometry {
    double len1, len2, base1, base2, zoff, bend1, bend2, assembly, margin_tan;
    double t1_min, t1_max, t2_min, t2_max;
};

static void read_geometry(struct geometry *g) {
    struct __comp_state *__comp_inst = robot;
    g->len1 = l1;
    g->len2 = l2;
    g->base1 = b1x;
    g->base2 = b2x;
    g->zoff = lp;
    g->bend1 = sigma1 < 0.0 ? -1.0 : 1.0;
    g->bend2 = sigma2 < 0.0 ? -1.0 : 1.0;
    g->assembly = sigma_a < 0.0 ? -1.0 : 1.0;
    g->margin_tan = tan(margin * DEGREE);
    g->t1_min = theta1_min * DEGREE;
    g->t1_max = theta1_max * DEGREE;
    g->t2_min = theta2_min * DEGREE;
    g->t2_max = theta2_max * DEGREE;
}

/* Wraps an angle into (-pi, pi]. */
static double wrap_angle(double angle) {
    double wrapped = fmod(angle, TAU);
    if (wrapped < 0.0) wrapped += TAU;
    return wrapped > M_PI ? wrapped - TAU : wrapped;
}

/* a - b wrapped into (-pi, pi], for a and b in [-pi, pi]. */
static double wrap_difference(double a, double b) {
    double difference = a - b;
    if (difference > M_PI) return difference - TAU;
    if (difference <= -M_PI) return difference + TAU;
    return difference;
}

/* Moves an angle by 2 pi when only that puts it inside [min, max]. */
static double fit_into(double angle, double min, double max) {
    if (angle < min && angle + TAU >= min && angle + TAU <= max) return angle + TAU;
    if (angle > max && angle - TAU >= min && angle - TAU <= max) return angle - TAU;
    return angle;
}

static double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

/* Solves A cos(theta) + B sin(theta) = C for the chain whose base joint is at (bx, 0), taking
   the root that bends by sigma. Returns -1 when the chain cannot reach (x, y). */
static int chain_inverse(const struct geometry *g, double bx, double sigma, double x, double y,
                         double *theta, double *ex, double *ey) {
    double dx = x - bx;
    double a = -y, b = dx;
    double reach2 = dx * dx + y * y;
    double c = (g->len2 * g->len2 - g->len1 * g->len1 - reach2) / (2.0 * g->len1);
    double discriminant = reach2 - c * c;
    double root, cos_theta, sin_theta, scale;
    if (discriminant < 0.0 || reach2 == 0.0) return -1;
    root = sigma * sqrt(discriminant);
    cos_theta = a * c - b * root;
    sin_theta = b * c + a * root;
    scale = g->len1 / reach2;
    *ex = bx - scale * sin_theta;
    *ey = scale * cos_theta;
    *theta = atan2(sin_theta, cos_theta);
    return 0;
}

/* The platform point for theta1, theta2 (radians) in the assembly mode: the intersection of
   the circles of radius l2 about the elbows. Returns -1 when the distal links cannot meet. */
static int planar_forward(const struct geometry *g, double theta1, double theta2,
                          double *e1x, double *e1y, double *px, double *py) {
    double e2x = g->base2 - g->len1 * sin(theta2), e2y = g->len1 * cos(theta2);
    double bx, by, distance2, height2, distance, height;
    *e1x = g->base1 - g->len1 * sin(theta1);
    *e1y = g->len1 * cos(theta1);
    bx = e2x - *e1x;
    by = e2y - *e1y;
    distance2 = bx * bx + by * by;
    height2 = g->len2 * g->len2 - 0.25 * distance2;
    if (!(height2 >= 0.0) || distance2 == 0.0) return -1;
    distance = sqrt(distance2);
    height = g->assembly * sqrt(height2);
    /* P = middle - sigma_a h n, with n = (E2 - E1) turned by +90 degrees, unit length. */
    *px = 0.5 * (*e1x + e2x) - height * (-by / distance);
    *py = 0.5 * (*e1y + e2y) - height * (bx / distance);
    return 0;
}

/* The angle of chain 1's distal link at the home pose (all joints 0), radians. */
static int distal_home(const struct geometry *g, double *psi1_home) {
    double e1x, e1y, px, py;
    if (planar_forward(g, 0.0, 0.0, &e1x, &e1y, &px, &py)) return -1;
    *psi1_home = atan2(py - e1y, px - e1x);
    return 0;
}

/* Outside the singularity margin: the angle between the lines along a and b is at least the
   margin, tested as |a x b| >= tan(margin) |a . b|. */
static int clear_of(const struct geometry *g, double ax, double ay, double bx, double by) {
    return fabs(cross(ax, ay, bx, by)) >= g->margin_tan * fabs(ax * bx + ay * by);
}

int kinematicsInverse(const EmcPose *pos, double *joints,
                      const KINEMATICS_INVERSE_FLAGS *iflags,
                      KINEMATICS_FORWARD_FLAGS *fflags) {
    struct geometry g;
    double x = pos->tran.x, y = pos->tran.y;
    double theta1, theta2, e1x, e1y, e2x, e2y, z1x, z1y, z2x, z2y, psi1_home;
    double theta3, current3;
    (void)iflags;
    (void)fflags;
    if (!robot) return -1;
    read_geometry(&g);
    if (!isfinite(x) || !isfinite(y) || !isfinite(pos->tran.z) || !isfinite(pos->c)) return -1;
    /* A chain that cannot reach the point. */
    if (chain_inverse(&g, g.base1, g.bend1, x, y, &theta1, &e1x, &e1y)) return -1;
    if (chain_inverse(&g, g.base2, g.bend2, x, y, &theta2, &e2x, &e2y)) return -1;
    z1x = x - e1x;
    z1y = y - e1y;
    z2x = x - e2x;
    z2y = y - e2y;
    /* The other assembly mode: beyond a type-2 singularity. */
    if ((cross(z2x, z2y, z1x, z1y) < 0.0 ? -1.0 : 1.0) != g.assembly) return -1;
    /* Inside the singularity margin of a type-1 (either chain) or type-2 singularity. */
    if (!clear_of(&g, e1x - g.base1, e1y, z1x, z1y) || !clear_of(&g, e2x - g.base2, e2y, z2x, z2y)
        || !clear_of(&g, z2x, z2y, z1x, z1y)) return -1;
    if (distal_home(&g, &psi1_home)) return -1;
    theta3 = pos->c - wrap_difference(atan2(z1y, z1x), psi1_home) / DEGREE;
    /* theta3 turns continuously: the value nearest its current one. */
    current3 = joints[3];
    if (isfinite(current3)) theta3 += 360.0 * rint((current3 - theta3) / 360.0);
    joints[0] = fit_into(theta1, g.t1_min, g.t1_max) / DEGREE;
    joints[1] = fit_into(theta2, g.t2_min, g.t2_max) / DEGREE;
    joints[2] = g.zoff - pos->tran.z;
    joints[3] = theta3;
    return 0;
}

int kinematicsForward(const double *joints, EmcPose *pos,
                      const KINEMATICS_FORWARD_FLAGS *fflags,
                      KINEMATICS_INVERSE_FLAGS *iflags) {
    struct geometry g;
    double e1x, e1y, px, py, psi1_home;
    (void)fflags;
    (void)iflags;
    if (!robot) return -1;
    read_geometry(&g);
    if (planar_forward(&g, joints[0] * DEGREE, joints[1] * DEGREE, &e1x, &e1y, &px, &py)) return -1;
    if (distal_home(&g, &psi1_home)) return -1;
    pos->tran.x = px;
    pos->tran.y = py;
    pos->tran.z = g.zoff - joints[2];
    pos->a = 0.0;
    pos->b = 0.0;
    pos->c = joints[3] + wrap_difference(atan2(py - e1y, px - e1x), psi1_home) / DEGREE;
    pos->u = 0.0;
    pos->v = 0.0;
    pos->w = 0.0;
    return 0;
}

int kinematicsHome(EmcPose *world, double *joints,
                   KINEMATICS_FORWARD_FLAGS *fflags,
                   KINEMATICS_INVERSE_FLAGS *iflags) {
    int i;
    for (i = 0; i < 4; i++) joints[i] = 0.0;
    *fflags = 0;
    *iflags = 0;
    return kinematicsForward(joints, world, fflags, iflags);
}

KINEMATICS_TYPE kinematicsType(void) {
    return KINEMATICS_BOTH;
}

KINS_NOT_SWITCHABLE
EXPORT_SYMBOL(kinematicsType);
EXPORT_SYMBOL(kinematicsForward);
EXPORT_SYMBOL(kinematicsInverse);
EXPORT_SYMBOL(kinematicsHome);
