/*
 * quads.c: a small fixed-function OpenGL 1.x program that draws known
 * geometry, for capturing with apitrace (tests/gl/capture.sh) and reading
 * back with wasp-gltrace and `wasp import-gl`.
 *
 * It opens a 256x128 GLX window and draws FRAMES frames, each ending with
 * glXSwapBuffers:
 *   - a perspective pass (glFrustum): two overlapping textured quads drawn
 *     with client arrays and glDrawElements(GL_TRIANGLES), the first
 *     through a texture matrix, then a triangle strip and a fan
 *     (glDrawArrays), with depth test (GL_LEQUAL) and back-face culling;
 *   - an orthographic pass (glOrtho): a GL_QUADS quad, a blended quad
 *     (glBlendFunc, depth writes off) and an alpha-tested quad
 *     (glAlphaFunc), inside a scissor rectangle.
 * Texture 1 is 8x8 RGBA with two mip levels (8x8 and 4x4) uploaded by
 * glTexImage2D; texture 2 is 4x4 RGBA, one level, with a transparent
 * checkerboard for the alpha test. The geometry moves by a few units per
 * frame so the frames differ.
 */
#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <stdio.h>
#include <stdlib.h>

#define WIDTH 256
#define HEIGHT 128
#define FRAMES 3

static GLuint textures[2];

static void upload_textures(void)
{
    GLubyte level0[8 * 8 * 4], level1[4 * 4 * 4], checker[4 * 4 * 4];
    int i;

    for (i = 0; i < 8 * 8; ++i) {
        int x = i % 8, y = i / 8;
        level0[4 * i + 0] = (GLubyte)(x * 32);
        level0[4 * i + 1] = (GLubyte)(y * 32);
        level0[4 * i + 2] = 128;
        level0[4 * i + 3] = 255;
    }
    for (i = 0; i < 4 * 4; ++i) {
        level1[4 * i + 0] = 200;
        level1[4 * i + 1] = (GLubyte)(i * 16);
        level1[4 * i + 2] = 40;
        level1[4 * i + 3] = 255;
    }
    for (i = 0; i < 4 * 4; ++i) {
        int on = ((i % 4) + (i / 4)) % 2;
        checker[4 * i + 0] = 255;
        checker[4 * i + 1] = 255;
        checker[4 * i + 2] = on ? 0 : 255;
        checker[4 * i + 3] = on ? 255 : 0;
    }

    glGenTextures(2, textures);
    glBindTexture(GL_TEXTURE_2D, textures[0]);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 8, 8, 0, GL_RGBA, GL_UNSIGNED_BYTE, level0);
    glTexImage2D(GL_TEXTURE_2D, 1, GL_RGBA, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, level1);

    glBindTexture(GL_TEXTURE_2D, textures[1]);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, checker);
}

/* The perspective pass: quads at depth -3 (behind) and -2.5 (in front). */
static void draw_perspective(int frame)
{
    static const GLfloat quads[] = {
        /* back quad */
        -1.5f, -1.0f, -3.0f, 0.5f, -1.0f, -3.0f, 0.5f, 1.0f, -3.0f, -1.5f, 1.0f, -3.0f,
        /* front quad, overlapping the back one */
        -0.5f, -0.5f, -2.5f, 1.5f, -0.5f, -2.5f, 1.5f, 0.8f, -2.5f, -0.5f, 0.8f, -2.5f,
    };
    static const GLfloat uvs[] = {
        0, 0, 1, 0, 1, 1, 0, 1,
        0, 0, 2, 0, 2, 2, 0, 2,
    };
    static const GLushort indices[] = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
    static const GLfloat strip[] = {
        -2.0f, -1.2f, -4.0f, -1.0f, -1.2f, -4.0f, -2.0f, -0.2f, -4.0f, -1.0f, -0.2f, -4.0f,
    };
    static const GLfloat fan[] = {
        1.5f, 0.0f, -3.5f, 2.0f, -0.5f, -3.5f, 2.2f, 0.3f, -3.5f, 1.7f, 0.8f, -3.5f,
    };
    static const GLfloat fan_uvs[] = {0.5f, 0.5f, 1, 0, 1, 1, 0, 1};

    glViewport(0, 0, WIDTH, HEIGHT);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-1.0, 1.0, -0.5, 0.5, 1.0, 10.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glTranslatef(0.1f * (GLfloat)frame, 0.0f, 0.0f);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, textures[0]);

    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, quads);
    glTexCoordPointer(2, GL_FLOAT, 0, uvs);

    /* The back quad through a texture matrix that scales by 2. */
    glMatrixMode(GL_TEXTURE);
    glLoadIdentity();
    glScalef(2.0f, 2.0f, 1.0f);
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, indices);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glDrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_SHORT, indices + 6);

    glVertexPointer(3, GL_FLOAT, 0, strip);
    glTexCoordPointer(2, GL_FLOAT, 0, uvs);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);

    glVertexPointer(3, GL_FLOAT, 0, fan);
    glTexCoordPointer(2, GL_FLOAT, 0, fan_uvs);
    glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
}

/* The orthographic pass, in pixels, inside a scissor rectangle. */
static void draw_ortho(int frame)
{
    GLfloat x = 8.0f * (GLfloat)frame;
    GLfloat opaque[] = {16 + x, 16, 0, 80 + x, 16, 0, 80 + x, 64, 0, 16 + x, 64, 0};
    GLfloat blended[] = {48 + x, 40, 0, 128 + x, 40, 0, 128 + x, 100, 0, 48 + x, 100, 0};
    GLfloat tested[] = {150, 20, 0, 230, 20, 0, 230, 100, 0, 150, 100, 0};
    static const GLfloat uvs[] = {0, 0, 1, 0, 1, 1, 0, 1};
    static const GLubyte colors[] = {
        255, 255, 255, 128, 255, 255, 255, 128, 255, 255, 255, 128, 255, 255, 255, 128,
    };

    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0.0, WIDTH, 0.0, HEIGHT, -1.0, 1.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();

    glEnable(GL_SCISSOR_TEST);
    glScissor(8, 8, 240, 112);
    glDisable(GL_CULL_FACE);
    glDepthFunc(GL_ALWAYS);
    glTexCoordPointer(2, GL_FLOAT, 0, uvs);

    /* An opaque quad. */
    glVertexPointer(3, GL_FLOAT, 0, opaque);
    glDrawArrays(GL_QUADS, 0, 4);

    /* A half-transparent quad over it: blended, no depth writes. */
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glEnableClientState(GL_COLOR_ARRAY);
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, colors);
    glVertexPointer(3, GL_FLOAT, 0, blended);
    glDrawArrays(GL_QUADS, 0, 4);
    glDisableClientState(GL_COLOR_ARRAY);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);

    /* A checkerboard quad with the transparent texels cut by the alpha test. */
    glBindTexture(GL_TEXTURE_2D, textures[1]);
    glEnable(GL_ALPHA_TEST);
    glAlphaFunc(GL_GREATER, 0.5f);
    glVertexPointer(3, GL_FLOAT, 0, tested);
    glDrawArrays(GL_QUADS, 0, 4);
    glDisable(GL_ALPHA_TEST);
    glDisable(GL_SCISSOR_TEST);
}

int main(void)
{
    int attribs[] = {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 24, None};
    Display *dpy = XOpenDisplay(NULL);
    XVisualInfo *vi;
    XSetWindowAttributes swa;
    Window win;
    GLXContext ctx;
    int frame;

    if (!dpy) {
        fprintf(stderr, "quads: cannot open the X display (run under xvfb-run)\n");
        return 1;
    }
    vi = glXChooseVisual(dpy, DefaultScreen(dpy), attribs);
    if (!vi) {
        fprintf(stderr, "quads: no RGBA double-buffered visual with a depth buffer\n");
        return 1;
    }
    swa.colormap = XCreateColormap(dpy, RootWindow(dpy, vi->screen), vi->visual, AllocNone);
    swa.event_mask = ExposureMask;
    win = XCreateWindow(dpy, RootWindow(dpy, vi->screen), 0, 0, WIDTH, HEIGHT, 0, vi->depth,
                        InputOutput, vi->visual, CWColormap | CWEventMask, &swa);
    XMapWindow(dpy, win);
    ctx = glXCreateContext(dpy, vi, NULL, True);
    if (!ctx || !glXMakeCurrent(dpy, win, ctx)) {
        fprintf(stderr, "quads: cannot create or bind a GLX context\n");
        return 1;
    }

    upload_textures();
    for (frame = 0; frame < FRAMES; ++frame) {
        glViewport(0, 0, WIDTH, HEIGHT);
        glClearColor(0.1f, 0.2f, 0.3f, 1.0f);
        glClearDepth(1.0);
        glDepthMask(GL_TRUE);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        draw_perspective(frame);
        draw_ortho(frame);
        glXSwapBuffers(dpy, win);
    }

    glXMakeCurrent(dpy, None, NULL);
    glXDestroyContext(dpy, ctx);
    XDestroyWindow(dpy, win);
    XFree(vi);
    XCloseDisplay(dpy);
    return 0;
}
